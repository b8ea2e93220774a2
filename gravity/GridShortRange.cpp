#include "gravity/GridShortRange.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace regolith::gravity {

namespace {

/// 26 directions (cube faces, edges and corners), normalised: a cheap, symmetric cover of
/// the sphere for the radial average.
std::vector<core::Vec3> directions() {
    std::vector<core::Vec3> out;
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x)
                if (x != 0 || y != 0 || z != 0)
                    out.push_back(core::Vec3(x, y, z).normalized());
    return out;
}

} // namespace

GridShortRange::GridShortRange(core::Comm const& comm, GridGravity& gravity, double cutoffCells)
    : m_G(gravity.solver().G()) {
    if (!(cutoffCells >= 2.0))
        throw core::InputError("gravity.p3m_cutoff: expected at least 2 cells");
    auto const& layout = gravity.layout();
    double const h = layout.spacing().minCoeff();
    m_cutoff = cutoffCells * h;
    m_dr = 0.125 * h;
    auto const samples = static_cast<std::size_t>(std::ceil(m_cutoff / m_dr)) + 1;
    m_table.assign(samples, 0.0);
    core::Vec3 const centre = layout.forest().domain().center();
    auto const dirs = directions();
    // Source positions at several sub-cell offsets, so that the table averages over where a
    // grain sits in its cell as well as over directions.
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
        std::vector<core::Vec3> probes;
        if (comm.rank() == 0)
            for (std::size_t k = 0; k < samples; ++k)
                for (auto const& d : dirs)
                    probes.push_back(source + static_cast<double>(k + 1) * m_dr * d);
        std::vector<core::Vec3> g(probes.size());
        gravity.accelerations({probes, {}, {}}, g);
        if (comm.rank() == 0)
            for (std::size_t k = 0; k < samples; ++k)
                for (std::size_t d = 0; d < dirs.size(); ++d)
                    m_table[k] += -g[k * dirs.size() + d].dot(dirs[d]); // towards the source
    }
    comm.allReduceInPlace(std::span<double>(m_table), core::ReduceOp::Sum);
    for (double& v : m_table)
        v /= static_cast<double>(offsets.size() * dirs.size());
    // The pair potential from the force table, integrated inwards from the cut-off: the
    // trapezoid rule on the table's own spacing is exact for its linear interpolation.
    auto const steps = static_cast<std::size_t>(std::ceil(m_cutoff / m_dr));
    m_integral.assign(steps + 1, 0.0);
    for (std::size_t k = steps; k-- > 0;) {
        double const a = static_cast<double>(k) * m_dr;
        double const b = std::min(a + m_dr, m_cutoff);
        m_integral[k] =
            m_integral[k + 1] + 0.5 * (b - a) * (meshPairAcceleration(a) + meshPairAcceleration(b));
    }
}

double GridShortRange::meshPairAcceleration(double r) const {
    double const u = r / m_dr - 1.0; // table index of r
    if (u <= 0.0) // below the first sample: the mesh force vanishes linearly at r = 0
        return m_table.front() * r / m_dr;
    auto const k = static_cast<std::size_t>(u);
    if (k + 1 >= m_table.size())
        return m_table.back();
    double const f = u - static_cast<double>(k);
    return (1.0 - f) * m_table[k] + f * m_table[k + 1];
}

core::Vec3 GridShortRange::correction(core::Vec3 const& d, double mj) const {
    double const r = d.norm();
    if (r >= m_cutoff || r == 0.0)
        return core::Vec3::Zero();
    return m_G * mj * (1.0 / (r * r) - meshPairAcceleration(r)) * (d / r);
}

double GridShortRange::pairFactor(double r, double softening) const {
    if (r >= m_cutoff || r == 0.0)
        return 0.0;
    double const s2 = r * r + softening * softening;
    return m_G * (1.0 / (s2 * std::sqrt(s2)) - meshPairAcceleration(r) / r);
}

double GridShortRange::pairPotential(double r, double softening) const {
    if (r >= m_cutoff)
        return 0.0;
    double const u = r / m_dr;
    auto const k = std::min(static_cast<std::size_t>(u), m_integral.size() - 2);
    double const f = std::min(u - static_cast<double>(k), 1.0);
    double const integral = (1.0 - f) * m_integral[k] + f * m_integral[k + 1];
    double const meshPsi = 1.0 / m_cutoff + integral;
    return -m_G * (1.0 / std::sqrt(r * r + softening * softening) - meshPsi);
}

double GridShortRange::selfPotential() const {
    return -m_G * (1.0 / m_cutoff + m_integral.front());
}

} // namespace regolith::gravity
