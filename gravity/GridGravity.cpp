#include "gravity/GridGravity.hpp"

#include "core/Error.hpp"
#include "gravity/poisson/Gradient.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

namespace regolith::gravity {

namespace {

GridGravityOptions const& validated(GridGravityOptions const& o) {
    if (!std::isfinite(o.poisson.G) || o.poisson.G <= 0.0)
        throw core::InputError(
            fmt::format("gravity.G: expected a positive number, got {}", o.poisson.G));
    if (o.gradientOrder != 2 && o.gradientOrder != 4)
        throw core::InputError(
            fmt::format("gravity.gradient_order: expected 2 or 4, got {}", o.gradientOrder));
    return o;
}

} // namespace

GridGravity::GridGravity(core::Comm const& comm, domain::BlockForest const& forest,
                         std::array<int, 3> cellsPerBlock, GridGravityOptions options)
    : m_comm(comm.duplicate())
    , m_options(validated(options))
    , m_layout(m_comm, forest, cellsPerBlock, m_options.gradientOrder / 2)
    , m_ghosts(m_comm, m_layout)
    , m_transfer(m_comm, m_layout, m_options.assignment)
    , m_density(m_layout)
    , m_potential(m_layout)
    , m_acceleration(m_layout, 3) {
    if (m_options.poissonMethod == PoissonMethod::Fft) {
        m_fft = std::make_unique<FftFreeSpace>(m_comm, m_layout, m_options.poisson.G);
    } else {
        m_solver = std::make_unique<PoissonSolver>(m_comm, m_layout, m_options.poisson);
        m_periodic = m_solver->periodic();
    }
    if (!m_periodic)
        listBoundaryGhosts();
}

void GridGravity::resetInitialGuess() {
    if (m_solver)
        m_solver->resetInitialGuess();
}

SolveStats GridGravity::update(Grains const& grains) {
    m_density.fill(0.0);
    m_transfer.deposit(grains, m_density);
    return solveFromDensity();
}

SolveStats GridGravity::solveFromDensity() {
    SolveStats stats;
    if (m_fft) {
        stats.solveSeconds = m_fft->solve(m_density, m_potential);
        m_boundary.update(m_comm, m_density, m_options.poisson.G);
    } else {
        stats = m_solver->solve(m_density, m_potential);
    }
    // The potential's ghost layers: neighbours' cells by exchange, while the free-space
    // boundary values are computed (they do not depend on the messages).
    m_ghosts.start(m_potential);
    if (!m_periodic)
        fillBoundaryGhosts();
    m_ghosts.wait(m_potential);
    negativeGradient(m_potential, m_acceleration, m_options.gradientOrder);
    return stats;
}

void GridGravity::listBoundaryGhosts() {
    auto const& n = m_layout.cellsPerBlock();
    int const g = m_layout.ghost();
    std::vector<GlobalCell> cells;
    std::vector<std::pair<std::size_t, std::size_t>> ghosts;
    for (std::size_t b = 0; b < m_layout.localBlockCount(); ++b) {
        auto const& o = m_layout.origin(b);
        for (int k = -g; k < n[2] + g; ++k)
            for (int j = -g; j < n[1] + g; ++j)
                for (int i = -g; i < n[0] + g; ++i) {
                    GlobalCell const c{o[0] + i, o[1] + j, o[2] + k};
                    if (m_layout.wrap(c))
                        continue;
                    cells.push_back(c);
                    ghosts.emplace_back(b, m_layout.padIndex(i, j, k));
                }
    }
    for (std::size_t i : FreeSpaceBoundary::coherentOrder(cells)) {
        m_boundaryGhosts.push_back(ghosts[i]);
        m_boundaryCentres.push_back(m_layout.centre(cells[i]));
    }
    m_boundaryPotential.resize(m_boundaryGhosts.size());
}

void GridGravity::fillBoundaryGhosts() {
    FreeSpaceBoundary const& boundary = m_solver ? m_solver->boundary() : m_boundary;
    boundary.evaluate(m_boundaryCentres, m_boundaryPotential);
    for (std::size_t i = 0; i < m_boundaryGhosts.size(); ++i) {
        auto const [b, pad] = m_boundaryGhosts[i];
        m_potential.block(b)[pad] = m_boundaryPotential[i];
    }
}

void GridGravity::accelerations(Grains const& grains, std::span<core::Vec3> out) {
    if (out.size() != grains.position.size())
        throw core::Error("GridGravity::accelerations: output size does not match the grains");
    std::vector<double> flat(3 * out.size());
    m_transfer.interpolate(grains, m_acceleration, flat);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = core::Vec3{flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
}

double GridGravity::potentialEnergy(Grains const& grains) {
    std::vector<double> phi(grains.position.size());
    m_transfer.interpolate(grains, m_potential, phi);
    double local = 0.0;
    for (std::size_t i = 0; i < phi.size(); ++i)
        local += 0.5 * grains.mass[i] * phi[i];
    return m_comm.allReduce(local, core::ReduceOp::Sum);
}

} // namespace regolith::gravity
