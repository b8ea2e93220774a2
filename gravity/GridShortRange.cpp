#include "gravity/GridShortRange.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace regolith::gravity {

namespace {
double checkedCutoff(GridGravity const& gravity, double cutoffCells) {
    if (!(cutoffCells >= 2.0))
        throw core::InputError("gravity.p3m_cutoff: expected at least 2 cells");
    return cutoffCells * gravity.layout().spacing().minCoeff();
}
} // namespace

GridShortRange::GridShortRange(core::Comm const& comm, GridGravity& gravity, double cutoffCells)
    : m_G(gravity.G())
    , m_cutoff(checkedCutoff(gravity, cutoffCells))
    , m_table(comm, gravity, m_cutoff) {
    auto const& layout = gravity.layout();
    double const h = layout.spacing().minCoeff();
    m_dv = 0.25 * h;
    m_half = static_cast<int>(std::ceil(m_cutoff / m_dv));
    int const side = 2 * m_half + 1;
    std::vector<double> vector(3 * static_cast<std::size_t>(side * side * side), 0.0);
    core::Vec3 const centre = layout.forest().domain().center();
    // Source positions at several sub-cell offsets, so that the tables average over where a
    // grain sits in its cell (the lattice symmetries below multiply them by up to 48).
    std::array<core::Vec3, 4> const offsets{core::Vec3{0.0, 0.0, 0.0}, core::Vec3{0.5, 0.5, 0.5},
                                            core::Vec3{0.25, 0.1, 0.4}, core::Vec3{0.5, 0.0, 0.25}};
    for (auto const& off : offsets) {
        core::Vec3 const source = centre + h * off;
        std::vector<core::Vec3> src;
        std::vector<double> mass;
        if (comm.rank() == 0) {
            src.push_back(source);
            mass.push_back(1.0 / m_G); // unit G m
        }
        gravity.update({src, {}, mass});
        // Probes: the lattice of displacements.
        std::vector<core::Vec3> probes;
        if (comm.rank() == 0) {
            for (int k = -m_half; k <= m_half; ++k)
                for (int j = -m_half; j <= m_half; ++j)
                    for (int i = -m_half; i <= m_half; ++i)
                        probes.push_back(source + m_dv * core::Vec3(i, j, k));
        }
        std::vector<core::Vec3> g(probes.size());
        gravity.accelerations({probes, {}, {}}, g);
        if (comm.rank() == 0)
            for (std::size_t v = 0; v < g.size(); ++v)
                for (int a = 0; a < 3; ++a)
                    vector[3 * v + static_cast<std::size_t>(a)] += g[v][a];
    }
    comm.allReduceInPlace(std::span<double>(vector), core::ReduceOp::Sum);
    for (double& v : vector)
        v /= static_cast<double>(offsets.size());
    symmetrise(vector, layout.spacing());
    // The grains' first solve must not start from the unit sources' potential: with a
    // periodic domain its residual exceeded PETSc's divergence bound before the first step.
    gravity.resetInitialGuess();
}

void GridShortRange::symmetrise(std::vector<double> const& raw, core::Vec3 const& spacing) {
    // The mesh is invariant under the lattice's symmetries about a source (reflections of each
    // axis; with cubic cells also permutations of the axes), which map one source offset to
    // another: averaging T(P e) mapped back by P^-1 over the group P averages over the mapped
    // offsets too, and makes the table odd, T(-e) = -T(e), so the correction conserves
    // momentum pair by pair.
    auto const perms = axisPermutations(spacing);
    int const side = 2 * m_half + 1;
    auto index = [&](std::array<int, 3> const& e) {
        return static_cast<std::size_t>((e[0] + m_half) +
                                        side * ((e[1] + m_half) + side * (e[2] + m_half)));
    };
    m_vector.assign(static_cast<std::size_t>(side * side * side), core::Vec3::Zero());
    double const count = static_cast<double>(perms.size() * 8);
    for (int k = -m_half; k <= m_half; ++k)
        for (int j = -m_half; j <= m_half; ++j)
            for (int i = -m_half; i <= m_half; ++i) {
                std::array<int, 3> const e{i, j, k};
                core::Vec3 sum = core::Vec3::Zero();
                for (auto const& p : perms)
                    for (int signs = 0; signs < 8; ++signs) {
                        std::array<int, 3> w{};
                        std::array<double, 3> s{};
                        for (std::size_t a = 0; a < 3; ++a) {
                            s[a] = ((signs >> a) & 1) != 0 ? -1.0 : 1.0;
                            w[a] = static_cast<int>(s[a]) * e[static_cast<std::size_t>(p[a])];
                        }
                        std::size_t const v = index(w);
                        for (std::size_t a = 0; a < 3; ++a)
                            sum[p[a]] += s[a] * raw[3 * v + a];
                    }
                m_vector[index(e)] = sum / count;
            }
}

core::Vec3 GridShortRange::meshPairVector(core::Vec3 const& e) const {
    int const side = 2 * m_half + 1;
    std::array<int, 3> i0{};
    std::array<double, 3> f{};
    for (std::size_t a = 0; a < 3; ++a) {
        double const u =
            std::clamp(e[static_cast<int>(a)] / m_dv + m_half, 0.0, static_cast<double>(side - 1));
        i0[a] = std::min(static_cast<int>(u), side - 2);
        f[a] = u - i0[a];
    }
    core::Vec3 out = core::Vec3::Zero();
    for (int c = 0; c < 8; ++c) {
        double w = 1.0;
        std::size_t idx = 0;
        std::size_t stride = 1;
        for (std::size_t a = 0; a < 3; ++a) {
            int const bit = (c >> a) & 1;
            w *= bit != 0 ? f[a] : 1.0 - f[a];
            idx += static_cast<std::size_t>(i0[a] + bit) * stride;
            stride *= static_cast<std::size_t>(side);
        }
        out += w * m_vector[idx];
    }
    return out;
}

core::Vec3 GridShortRange::correction(core::Vec3 const& d, double mj) const {
    return mj * pairCorrection(d, 0.0);
}

core::Vec3 GridShortRange::pairCorrection(core::Vec3 const& d, double softening) const {
    double const r = d.norm();
    if (r >= m_cutoff || r == 0.0)
        return core::Vec3::Zero();
    double const s2 = r * r + softening * softening;
    // Grain i sits at -d from the source j: the mesh gave it T(-d) = -T(d).
    return m_G * (d / (s2 * std::sqrt(s2)) + meshPairVector(d));
}

double GridShortRange::pairPotential(core::Vec3 const& xi, core::Vec3 const& xj,
                                     double softening) const {
    double const r = (xj - xi).norm();
    if (r >= m_cutoff)
        return 0.0;
    return -m_G / std::sqrt(r * r + softening * softening) - m_table.meshPotential(xi, xj) +
           m_table.regular();
}

} // namespace regolith::gravity
