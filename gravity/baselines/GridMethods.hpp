#pragma once
/// The second paper's two grid methods, as baselines on the same scenes as the tree
/// (Nesmachnow, Rocchetti & Tancredi): accelerations at the nodes around occupied cells,
/// interpolated trilinearly to the grains (NodeGrid.hpp).
///  - OccupiedCells (`gravity.self = "occupied-cells"`, §4): every needed node sums the
///    field of every grain (the paper's Eq. 2, with the uniform-sphere field inside a grain).
///  - TreeAtNodes (`"tree-nodes"`, §5): an octree whose subdivision stops at the grid's box
///    size; each node walks it with the Barnes–Hut acceptance test and the paper's
///    neighbourhood rule (a cell that comes within `neighbourhood` of the node is opened),
///    opened leaves are summed grain by grain.
/// Both gather all grains on every rank (GatherAll.hpp); each rank computes the nodes its
/// own grains need.
#include "core/mpi/Comm.hpp"
#include "gravity/baselines/NodeGrid.hpp"
#include "gravity/common/PointMasses.hpp"

namespace regolith::gravity::baselines {

struct GridMethodOptions {
    double G = kNewtonG;  ///< `gravity.G`
    NodeGrid grid;        ///< `gravity.grid_origin`, `gravity.grid_spacing`
    bool expand64 = true; ///< the paper's 64-node expansion (else the 8 corners only)
    // tree-nodes only
    double theta = 0.5;           ///< `gravity.theta`
    bool allowLargeTheta = false; ///< `gravity.allow_large_theta`
    double neighbourhood = 0.0;   ///< `gravity.neighbourhood`, m
    bool quadrupole = false;      ///< the paper uses mass and centre of mass only
};

/// Throws core::InputError naming the key (`gravity.grid_spacing`, `gravity.theta`,
/// `gravity.neighbourhood`, `gravity.G`).
void validate(GridMethodOptions const& options);

struct GridStats {
    long long nodes = 0;        ///< nodes evaluated on this rank
    long long interactions = 0; ///< node–grain and node–cell evaluations on this rank
};

class OccupiedCells {
public:
    explicit OccupiedCells(GridMethodOptions const& options);
    /// Field at the local grains; overwrites `out`; returns the total ½ Σ m φ (J). Throws
    /// core::InputError on every rank for bad masses. COLLECTIVE over `comm`.
    double evaluate(core::Comm const& comm, PointMasses const& local, FieldOut out);
    [[nodiscard]] GridStats const& stats() const { return m_stats; }

private:
    GridMethodOptions m_options;
    GridStats m_stats;
};

class TreeAtNodes {
public:
    explicit TreeAtNodes(GridMethodOptions const& options);
    /// As OccupiedCells::evaluate. COLLECTIVE over `comm`.
    double evaluate(core::Comm const& comm, PointMasses const& local, FieldOut out);
    [[nodiscard]] GridStats const& stats() const { return m_stats; }

private:
    GridMethodOptions m_options;
    GridStats m_stats;
};

} // namespace regolith::gravity::baselines
