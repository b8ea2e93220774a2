#include "bench/gravity/MeshEvaluation.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>

namespace regolith::bench {

namespace {

double processCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

gravity::GridGravityOptions gridOptions(MeshSetup const& s) {
    gravity::GridGravityOptions o;
    o.assignment = s.assignment;
    o.gradientOrder = s.gradientOrder;
    o.poisson.G = gravity::kNewtonG;
    o.poisson.rtol = s.rtol;
    return o;
}

} // namespace

MeshEvaluation::MeshEvaluation(core::Comm const& comm, gravity::samples::Body const& body,
                               MeshSetup setup)
    : m_comm(comm.duplicate())
    , m_setup(setup) {
    core::Vec3 lo = core::Vec3::Constant(std::numeric_limits<double>::infinity());
    core::Vec3 hi = -lo;
    double rMax = 0.0;
    for (std::size_t i = 0; i < body.size(); ++i) {
        core::Vec3 const p{body.x[i], body.y[i], body.z[i]};
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        rMax = std::max(rMax, body.r.empty() ? 0.0 : body.r[i]);
    }
    // Mass reaches r + 1.5 h (TSC) from a centre; two more cells keep it off the boundary.
    double const half = 0.5 * (hi - lo).maxCoeff() + rMax + 4.0 * setup.spacing;
    int const blocks = comm.size();
    int const perBlock =
        std::max(4, static_cast<int>(std::ceil(2.0 * half / (setup.spacing * blocks))));
    m_cells = perBlock * blocks;
    m_spacing = 2.0 * half / m_cells;
    core::Vec3 const centre = 0.5 * (lo + hi);
    m_centre = centre;
    domain::ForestSpec spec;
    spec.domain =
        core::AABB{centre - core::Vec3::Constant(half), centre + core::Vec3::Constant(half)};
    spec.rootBlocks = {blocks, 1, 1};
    spec.cellsPerBlock = {perBlock, m_cells, m_cells};
    m_forest = std::make_unique<domain::BlockForest>(m_comm, spec);
    m_grid = std::make_unique<gravity::GridGravity>(m_comm, *m_forest, spec.cellsPerBlock,
                                                    gridOptions(m_setup));
}

MeshEvaluation::~MeshEvaluation() = default;

MeshTiming MeshEvaluation::evaluate(gravity::PointMasses const& local, gravity::FieldOut out) {
    if (m_used) {
        m_grid.reset(); // the old solver's memory first
        m_grid = std::make_unique<gravity::GridGravity>(
            m_comm, *m_forest, std::array<int, 3>{m_cells / m_comm.size(), m_cells, m_cells},
            gridOptions(m_setup));
    }
    m_used = true;
    // A first solve for a negligible mass at the centre does the AMG set-up (once per forest
    // in a run) and leaves an initial guess ~1e-12 of the true potential: the timed solve is
    // then a cold start without the set-up.
    double totalMass = 0.0;
    for (double m : local.m)
        totalMass += m;
    totalMass = m_comm.allReduce(totalMass, core::ReduceOp::Sum);
    std::vector<core::Vec3> seedPosition;
    std::vector<double> seedMass, seedRadius;
    if (m_comm.rank() == 0) {
        seedPosition.push_back(m_centre);
        seedMass.push_back(1e-12 * totalMass);
        seedRadius.push_back(0.0);
    }
    m_grid->update(gravity::Grains{seedPosition, seedRadius, seedMass});

    m_position.resize(local.size());
    for (std::size_t i = 0; i < local.size(); ++i)
        m_position[i] = core::Vec3{local.x[i], local.y[i], local.z[i]};
    gravity::Grains const grains{m_position, local.r, local.m};
    m_acceleration.resize(local.size());

    m_comm.barrier();
    double const t0 = MPI_Wtime();
    double const c0 = processCpuSeconds();
    gravity::SolveStats const stats = m_grid->update(grains);
    m_grid->accelerations(grains, m_acceleration);
    double const cpu = processCpuSeconds() - c0;
    double const wall = MPI_Wtime() - t0;
    for (std::size_t i = 0; i < local.size(); ++i) {
        out.ax[i] = m_acceleration[i].x();
        out.ay[i] = m_acceleration[i].y();
        out.az[i] = m_acceleration[i].z();
    }
    MeshTiming t;
    t.wall = m_comm.allReduce(wall, core::ReduceOp::Max);
    t.cpu = m_comm.allReduce(cpu, core::ReduceOp::Max);
    t.iterations = stats.iterations;
    return t;
}

} // namespace regolith::bench
