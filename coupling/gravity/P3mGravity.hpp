#pragma once
/// P3M self-gravity on the grains (`gravity.self = "p3m"`; Hockney & Eastwood, "Computer
/// Simulation Using Particles", ch. 7): the particle-mesh force of gravity/GridGravity plus,
/// for every pair closer than the cut-off (a few cells), the exact pair force minus the
/// mesh's own pair force (gravity/GridShortRange). The mesh gives the long range at the cost
/// of a Poisson solve, the pair sum the short range at the accuracy of the direct sum.
///
/// Grains are deposited as points (no volume), so that the mesh's pair force is the one the
/// correction table was calibrated for; outside each other two uniform spheres attract as
/// points, so nothing is lost. Pairs are found with the particle side's linked cells
/// (particles/detection/LinkedCells, cell edge = cut-off) over this rank's grains plus the
/// gravity-only halo of other ranks' grains within the cut-off (ShortRangeHalo).
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/SelfGravityForces.hpp"
#include "coupling/gravity/ShortRangeHalo.hpp"
#include "domain/BlockForest.hpp"
#include "gravity/GridGravity.hpp"
#include "gravity/GridShortRange.hpp"
#include "gravity/common/PointMasses.hpp"
#include "gravity/petsc/PetscSession.hpp"
#include "particles/detection/LinkedCells.hpp"

#include <vector>

namespace regolith::coupling {

/// The grid-gravity options of the mesh methods (pm, p3m) from the scene's configuration.
[[nodiscard]] gravity::GridGravityOptions gridGravityOptions(SelfGravityConfig const& c);

class P3mGravity {
public:
    /// Builds the grid (domain.cells_per_block), calibrates the pair table (four Poisson
    /// solves) and the halo plan. Throws core::InputError on every rank for the grid's errors
    /// (GridGravity), gravity.p3m_cutoff < 2, or a grid with fewer than 2 cut-offs + 4 cells
    /// on an axis (the calibration needs that room). COLLECTIVE over `comm`.
    P3mGravity(core::Comm const& comm, domain::BlockForest const& forest,
               SelfGravityConfig const& config);

    /// Acceleration at every local grain (overwrites `out`; positions inside the domain,
    /// wrapped on periodic axes as the synchronisation leaves masters). Returns the potential
    /// energy ½ Σ m φ over all ranks, pairs only (the mesh's self-energy of each grain is
    /// removed), in J. COLLECTIVE.
    double evaluate(gravity::PointMasses const& grains, gravity::FieldOut out);

    [[nodiscard]] gravity::GridGravity const& grid() const { return m_grid; }
    /// The next solve starts from zero (GridGravity::resetInitialGuess). Not collective.
    void resetInitialGuess() { m_grid.resetInitialGuess(); }
    [[nodiscard]] gravity::GridShortRange const& shortRange() const { return m_shortRange; }
    [[nodiscard]] ShortRangeHalo const& halo() const { return m_halo; }
    /// Pairs corrected in the last evaluate() on this rank (a pair of two local grains
    /// counts once, a pair with a halo grain once on each side).
    [[nodiscard]] long long pairsLastEvaluate() const { return m_pairs; }
    /// The Poisson solve of the last evaluate().
    [[nodiscard]] gravity::SolveStats const& lastSolve() const { return m_lastSolve; }

private:
    /// Adds the short-range correction to m_acc; returns this rank's share of the energy
    /// correction.
    double addShortRange(gravity::PointMasses const& grains);

    int m_argc = 0;
    char** m_argv = nullptr;
    gravity::PetscSession m_session;
    core::Comm m_comm;
    domain::BlockForest const* m_forest;
    double m_softening;
    gravity::GridGravity m_grid;
    gravity::GridShortRange m_shortRange;
    ShortRangeHalo m_halo;
    particles::LinkedCells m_cells;
    long long m_pairs = 0;
    gravity::SolveStats m_lastSolve;
    // Scratch, reused between calls: local grains first, then the halo.
    std::vector<core::Vec3> m_position, m_acc;
    std::vector<double> m_mass, m_zeroRadius;
    std::vector<std::uint32_t> m_members;
};

} // namespace regolith::coupling
