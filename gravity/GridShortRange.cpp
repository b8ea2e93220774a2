#include "gravity/GridShortRange.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace regolith::gravity {

namespace {

/// The permutations of the axes that map the mesh onto itself: all six with cubic cells,
/// the identity otherwise (with the eight reflections, the lattice symmetries the tables are
/// averaged over).
std::vector<std::array<int, 3>> axisPermutations(core::Vec3 const& spacing) {
    if ((spacing.maxCoeff() - spacing.minCoeff()) <= 1e-12 * spacing.maxCoeff())
        return {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    return {{0, 1, 2}};
}

} // namespace

GridShortRange::GridShortRange(core::Comm const& comm, GridGravity& gravity, double cutoffCells)
    : m_layout(&gravity.layout())
    , m_assignment(gravity.assignment())
    , m_G(gravity.G()) {
    if (!(cutoffCells >= 2.0))
        throw core::InputError("gravity.p3m_cutoff: expected at least 2 cells");
    auto const& layout = gravity.layout();
    double const h = layout.spacing().minCoeff();
    m_cutoff = cutoffCells * h;
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
    measureCellPotential(comm, gravity, centre);
    // On a periodic domain the table also holds the images' and the background's potential:
    // its regular part at the cut-off stays in the corrections, so that they vanish there (no
    // jump in the energy as a pair crosses it) and each grain keeps its share with its own
    // images, as the Ewald sum has it. Averaged over the 26 directions of the cube's faces,
    // edges and corners. In free space the mesh is taken as exact from the cut-off on, as
    // the forces are (its ~0.4 % there would only shift every close pair's energy).
    double sum = 0.0;
    int count = 0;
    for (int z = -1; z <= 1 && gravity.periodic(); ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x)
                if (x != 0 || y != 0 || z != 0) {
                    core::Vec3 const d = core::Vec3(x, y, z).normalized();
                    sum += meshPotential(centre, centre + m_cutoff * d) + m_G / m_cutoff;
                    ++count;
                }
    m_regular = count > 0 ? sum / count : 0.0;
    // The grains' first solve must not start from the unit sources' potential: with a
    // periodic domain its residual exceeded PETSc's divergence bound before the first step.
    gravity.resetInitialGuess();
}

void GridShortRange::measureCellPotential(core::Comm const& comm, GridGravity& gravity,
                                          core::Vec3 const& source) {
    CellLayout const& layout = gravity.layout();
    // Offsets a pair inside the cut-off reaches: the cells between the two grains plus each
    // kernel's width (TSC: 3 cells, so the weights' offsets differ by up to 2 more).
    m_reach = static_cast<std::int64_t>(std::ceil(m_cutoff / layout.spacing().minCoeff())) + 3;
    auto const side = static_cast<std::size_t>(2 * m_reach + 1);
    core::Vec3 const u = layout.cellCoordinate(source);
    GlobalCell const cell{std::llround(u[0]), std::llround(u[1]), std::llround(u[2])};
    CellField& density = gravity.density();
    density.fill(0.0);
    auto const at = layout.owner(cell);
    if (!at)
        throw core::Error("GridShortRange: the calibration cell lies outside the domain");
    if (at->localBlock >= 0) // unit G m in one cell
        density.block(static_cast<std::size_t>(at->localBlock))[at->pad] =
            1.0 / (m_G * layout.cellVolume());
    gravity.solveFromDensity();
    // Each offset read where its cell lives (value, 1), summed over the ranks.
    std::vector<double> raw(2 * side * side * side, 0.0);
    CellField const& phi = gravity.potential();
    std::size_t v = 0;
    for (std::int64_t k = -m_reach; k <= m_reach; ++k)
        for (std::int64_t j = -m_reach; j <= m_reach; ++j)
            for (std::int64_t i = -m_reach; i <= m_reach; ++i, ++v) {
                auto const o = layout.owner({cell[0] + i, cell[1] + j, cell[2] + k});
                if (!o || o->localBlock < 0)
                    continue;
                raw[2 * v] = phi.block(static_cast<std::size_t>(o->localBlock))[o->pad];
                raw[2 * v + 1] = 1.0;
            }
    comm.allReduceInPlace(std::span<double>(raw), core::ReduceOp::Sum);
    // Averaged over the reflections (and the axis permutations of cubic cells) of the
    // offsets the domain holds: the free-space boundary breaks the symmetry only slightly.
    core::Vec3 const& h = layout.spacing();
    auto const perms = axisPermutations(h);
    auto index = [&](std::array<std::int64_t, 3> const& e) {
        auto const s = static_cast<std::int64_t>(side);
        return static_cast<std::size_t>((e[0] + m_reach) +
                                        s * ((e[1] + m_reach) + s * (e[2] + m_reach)));
    };
    m_cell.assign(side * side * side, 0.0);
    for (std::int64_t k = -m_reach; k <= m_reach; ++k)
        for (std::int64_t j = -m_reach; j <= m_reach; ++j)
            for (std::int64_t i = -m_reach; i <= m_reach; ++i) {
                std::array<std::int64_t, 3> const e{i, j, k};
                double sum = 0.0, count = 0.0;
                for (auto const& p : perms)
                    for (int signs = 0; signs < 8; ++signs) {
                        std::array<std::int64_t, 3> w{};
                        for (std::size_t a = 0; a < 3; ++a)
                            w[a] = (((signs >> a) & 1) != 0 ? -1 : 1) *
                                   e[static_cast<std::size_t>(p[a])];
                        sum += raw[2 * index(w)];
                        count += raw[2 * index(w) + 1];
                    }
                double const r =
                    core::Vec3(static_cast<double>(i) * h.x(), static_cast<double>(j) * h.y(),
                               static_cast<double>(k) * h.z())
                        .norm();
                m_cell[index(e)] = count > 0.0 ? sum / count : -1.0 / r;
            }
}

double GridShortRange::cellPotential(std::int64_t i, std::int64_t j, std::int64_t k) const {
    auto const s = 2 * m_reach + 1;
    return m_cell[static_cast<std::size_t>((i + m_reach) +
                                           s * ((j + m_reach) + s * (k + m_reach)))];
}

double GridShortRange::meshPotential(core::Vec3 const& xi, core::Vec3 const& xj) const {
    // Per axis, the two stencils' products summed by cell offset (cell of i minus cell of
    // j): the 3-D sum over both deposits factorises into these, 125 table reads for TSC.
    core::Vec3 const ui = m_layout->cellCoordinate(xi);
    core::Vec3 const uj = m_layout->cellCoordinate(xj);
    std::array<std::array<double, 5>, 3> weight{};
    std::array<std::int64_t, 3> lowest{};
    std::array<int, 3> width{};
    for (int a = 0; a < 3; ++a) {
        auto const ua = static_cast<std::size_t>(a);
        Stencil1D const si = stencil(m_assignment, ui[a]);
        Stencil1D const sj = stencil(m_assignment, uj[a]);
        lowest[ua] = si.first - sj.first - (sj.count - 1);
        width[ua] = si.count + sj.count - 1;
        for (int p = 0; p < si.count; ++p)
            for (int q = 0; q < sj.count; ++q)
                weight[ua][static_cast<std::size_t>(p - q + sj.count - 1)] +=
                    si.w[static_cast<std::size_t>(p)] * sj.w[static_cast<std::size_t>(q)];
    }
    for (std::size_t a = 0; a < 3; ++a)
        if (std::abs(lowest[a]) > m_reach || std::abs(lowest[a] + width[a] - 1) > m_reach)
            throw core::Error("GridShortRange::meshPotential: the grains are beyond the table");
    double sum = 0.0;
    for (int z = 0; z < width[2]; ++z)
        for (int y = 0; y < width[1]; ++y) {
            double const wyz =
                weight[1][static_cast<std::size_t>(y)] * weight[2][static_cast<std::size_t>(z)];
            for (int x = 0; x < width[0]; ++x)
                sum += weight[0][static_cast<std::size_t>(x)] * wyz *
                       cellPotential(lowest[0] + x, lowest[1] + y, lowest[2] + z);
        }
    return m_G * sum;
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
    return -m_G / std::sqrt(r * r + softening * softening) - meshPotential(xi, xj) + m_regular;
}

double GridShortRange::selfPotential(core::Vec3 const& x) const {
    return meshPotential(x, x) - m_regular;
}

} // namespace regolith::gravity
