#include "coupling/gravity/P3mGravity.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numeric>

namespace regolith::coupling {

gravity::GridGravityOptions gridGravityOptions(SelfGravityConfig const& c) {
    gravity::GridGravityOptions o;
    o.gradientOrder = c.gradientOrder;
    o.poisson.G = c.G;
    o.poisson.petscOptions = c.petscOptions;
    o.poisson.reproducible = c.reproducible;
    o.poissonMethod = c.poisson;
    return o;
}

namespace {

/// The calibration of GridShortRange puts a unit mass at the domain centre and probes the
/// mesh force out to the cut-off: the grid must hold the cut-off on both sides with a margin
/// of two cells for the kernel and the boundary. Same outcome on every rank.
gravity::GridGravity& checkedForCalibration(gravity::GridGravity& grid, double cutoffCells) {
    if (!(cutoffCells >= 2.0) || !std::isfinite(cutoffCells))
        throw core::InputError(fmt::format(
            "gravity.p3m_cutoff = {:g}: expected a finite number of cells >= 2", cutoffCells));
    auto const& layout = grid.layout();
    auto const needed = static_cast<std::int64_t>(std::ceil(2.0 * cutoffCells)) + 4;
    for (int a = 0; a < 3; ++a) {
        auto const have = layout.globalCells()[static_cast<std::size_t>(a)];
        if (have < needed)
            throw core::InputError(fmt::format(
                "domain.cells_per_block: gravity.self = \"p3m\" with gravity.p3m_cutoff = {:g} "
                "cells needs at least {} cells across the domain on every axis (2 cut-offs "
                "+ 4), axis {} has {}",
                cutoffCells, needed, a, have));
    }
    return grid;
}

} // namespace

P3mGravity::P3mGravity(core::Comm const& comm, domain::BlockForest const& forest,
                       SelfGravityConfig const& c)
    : m_session(m_argc, m_argv)
    , m_comm(comm.duplicate())
    , m_forest(&forest)
    , m_softening(c.softening)
    , m_grid(comm, forest, c.cellsPerBlock, gridGravityOptions(c))
    , m_shortRange(comm, checkedForCalibration(m_grid, c.p3mCutoffCells), c.p3mCutoffCells)
    , m_halo(comm, forest, m_grid.layout(), m_shortRange.cutoff()) {}

double P3mGravity::evaluate(gravity::PointMasses const& grains, gravity::FieldOut out) {
    std::size_t const n = grains.size();
    m_position.resize(n);
    for (std::size_t k = 0; k < n; ++k)
        m_position[k] = m_forest->wrap(core::Vec3(grains.x[k], grains.y[k], grains.z[k]));
    // Points: no radius (see the header).
    gravity::Grains const points{std::span<core::Vec3 const>(m_position.data(), n), {}, grains.m};
    m_lastSolve = m_grid.update(points);
    m_acc.resize(n);
    m_grid.accelerations(points, m_acc);
    double const meshEnergy = m_grid.potentialEnergy(points);
    double const correction = addShortRange(grains);
    for (std::size_t k = 0; k < n; ++k) {
        out.ax[k] = m_acc[k].x();
        out.ay[k] = m_acc[k].y();
        out.az[k] = m_acc[k].z();
    }
    return meshEnergy + m_comm.allReduce(correction, core::ReduceOp::Sum);
}

double P3mGravity::addShortRange(gravity::PointMasses const& grains) {
    std::size_t const n = grains.size();
    m_halo.gather(std::span<core::Vec3 const>(m_position.data(), n), grains.m);
    // Local grains first (indices < n), then the halo.
    m_position.resize(n);
    m_position.insert(m_position.end(), m_halo.position().begin(), m_halo.position().end());
    m_mass.assign(grains.m.begin(), grains.m.end());
    m_mass.insert(m_mass.end(), m_halo.mass().begin(), m_halo.mass().end());
    std::size_t const total = m_position.size();
    m_zeroRadius.assign(total, 0.0);
    m_members.resize(total);
    std::iota(m_members.begin(), m_members.end(), std::uint32_t{0});
    double const cutoff = m_shortRange.cutoff();
    // Points of radius 0 with slack = cut-off: the overlap test is |x_a - x_b| < cut-off.
    m_cells.build(m_position, m_zeroRadius, m_members, cutoff, 4 * total + 64, cutoff);
    double energy = 0.0;
    m_pairs = 0;
    m_cells.forEachOverlap([&](std::size_t a, std::size_t b) {
        if (a >= n && b >= n)
            return; // two halo grains: their own ranks handle them
        core::Vec3 const d = m_position[b] - m_position[a];
        double const r = d.norm();
        if (r == 0.0)
            return; // coincident grains exert nothing on each other, as in the direct sum
        core::Vec3 const correction = m_shortRange.pairCorrection(d, m_softening);
        double const potential =
            m_shortRange.pairPotential(m_position[a], m_position[b], m_softening);
        ++m_pairs;
        if (a < n) {
            m_acc[a] += m_mass[b] * correction;
            energy += 0.5 * m_mass[a] * m_mass[b] * potential;
        }
        if (b < n) {
            m_acc[b] -= m_mass[a] * correction;
            energy += 0.5 * m_mass[a] * m_mass[b] * potential;
        }
    });
    // The mesh potential at each grain includes the grain's own (mesh-softened) potential,
    // which depends on where it sits in its cell.
    for (std::size_t k = 0; k < n; ++k)
        energy -= 0.5 * m_mass[k] * m_mass[k] * m_shortRange.selfPotential(m_position[k]);
    return energy;
}

} // namespace regolith::coupling
