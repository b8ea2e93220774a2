#pragma once
/// The particle-mesh method (gravity/GridGravity: deposit, PETSc Poisson solve with the
/// free-space boundary, gradient, interpolation) as one more point of gravity_bench: a cube
/// of cells of a given spacing around a body, on a forest of one block per rank.
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "gravity/GridGravity.hpp"
#include "gravity/common/PointMasses.hpp"
#include "gravity/samples/SyntheticBodies.hpp"

#include <memory>
#include <vector>

namespace regolith::bench {

struct MeshSetup {
    double spacing = 1.0; ///< cell edge h, m
    int gradientOrder = 4;
    double rtol = 1e-6; ///< solver tolerance: well below the discretisation error (≥ 1e-4)
    gravity::Assignment assignment = gravity::Assignment::Tsc;
};

/// Wall and CPU seconds of one evaluation (slowest rank).
struct MeshTiming {
    double wall = 0.0;
    double cpu = 0.0;
    int iterations = 0;
};

class MeshEvaluation {
public:
    /// A free-space cube around all grains of `body` (the whole body, not a rank's share)
    /// with a margin of the kernel width, h = setup.spacing rounded so that the cube holds a
    /// whole number of cells per block. Pre: PETSc initialised. COLLECTIVE over `comm`.
    MeshEvaluation(core::Comm const& comm, gravity::samples::Body const& body, MeshSetup setup);
    ~MeshEvaluation();
    MeshEvaluation(MeshEvaluation const&) = delete;
    MeshEvaluation& operator=(MeshEvaluation const&) = delete;

    /// Field at this rank's grains `local` from all ranks' grains, from a cold start (the
    /// solver is rebuilt between calls, outside the timed part); the AMG set-up, done once per
    /// forest in a run, is not counted. COLLECTIVE.
    MeshTiming evaluate(gravity::PointMasses const& local, gravity::FieldOut out);

    [[nodiscard]] int cellsPerAxis() const { return m_cells; }
    [[nodiscard]] double spacing() const { return m_spacing; }

private:
    core::Comm m_comm;
    MeshSetup m_setup;
    int m_cells = 0;
    double m_spacing = 0.0;
    core::Vec3 m_centre = core::Vec3::Zero();
    std::unique_ptr<domain::BlockForest> m_forest;
    std::unique_ptr<gravity::GridGravity> m_grid;
    bool m_used = false; ///< m_grid has solved (its next solve would start warm)
    std::vector<core::Vec3> m_position, m_acceleration;
};

} // namespace regolith::bench
