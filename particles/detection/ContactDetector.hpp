#pragma once
/// Contact detection for one block that stays O(N) for strongly polydisperse scenes: linked
/// cells sized for the small grains, plus a separate pass for the few large ones.
#include "core/math/AABB.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/LinkedCells.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <cstddef>
#include <vector>

namespace regolith::particles {

struct DetectorConfig {
    /// Added to the cell edge 2 * r_small_max [length]; > 0 only pays off when the cells are
    /// reused, so 0 by default.
    double skin = 0.0;
    /// Spheres with a radius above this go to the large pass [length]; 0 = automatic:
    /// `largeFactor` times the median radius of the block's spheres.
    double largeRadius = 0.0;
    double largeFactor = 2.0;
    /// The cell grid has at most this many cells per small sphere (the edge grows otherwise).
    std::size_t maxCellsPerSphere = 8;
    /// Sort the output by (uid_i, uid_j) and (uid, wall), so that forces are summed in an
    /// order independent of storage order (reproducible mode). Costs O(C log C).
    bool sortByUid = false;
};

/// What the last `detect` call did (for tests and benchmarks).
struct DetectorStats {
    std::size_t smallSpheres = 0;
    std::size_t largeSpheres = 0;
    double largeThreshold = 0.0; ///< radius above which a sphere was large
    double cellEdge = 0.0;
    std::size_t cells = 0;
    std::size_t largeCellVisits = 0; ///< cells visited by the large pass in total
    std::size_t largeCandidates = 0; ///< sphere pairs the large pass tested
    std::size_t overlapsFound = 0;   ///< overlaps (Fixed pairs too) before the region filter
};

/// A region "this block evaluates contacts whose point lies in [min, max)" that contains
/// every point: for a single block.
core::AABB everywhere();

/// Finds the overlapping sphere pairs and sphere–wall contacts of a ParticleStorage.
///
/// Algorithm. Spheres with radius <= r_cut ("small") are binned into linked cells of edge
/// 2 * r_small_max + skin and tested against the same and the 13 forward neighbour cells, so
/// each small pair is seen once. Spheres above r_cut ("large") are not binned: each one
/// visits the cells its ball (radius r + r_small_max) covers, row by row, and the large ones
/// are tested against each other by sort-and-sweep along their axis of largest spread (Baraff,
/// "Dynamic simulation of non-penetrating rigid bodies", PhD thesis, Cornell 1992, ch. 6). Why:
/// with one cell size for all, a radius-30 sphere among radius-0.4 grains would force cells of edge
/// 60 holding ~10^5 grains each, O(N^2) work; with the large one inserted into every cell it
/// covers, every visit of one of those ~2 * 10^5 cells would test it. Here each small sphere costs
/// O(1) (bounded occupancy per cell) and each large sphere costs the number of cells in its ball,
/// which is the number of small grains that could fill that volume, so the total is O(N) in the
/// number of grains the scene could hold — the spirit of the multilevel grids of Ogarko &
/// Luding (Comput. Phys. Commun. 183 (2012) 931) with two levels. Pairs of two Fixed spheres
/// are skipped (neither can move).
///
/// Limits of the automatic threshold (2 x median radius): it suits "few large among many
/// small". If most grains are large (say 60 % of radius 10 among radius 0.4), the median is
/// large, the cells are sized for it and hold many small grains each; set
/// DetectorConfig::largeRadius for such mixtures.
///
/// Contact-point rule: only contacts whose point lies in `evaluationRegion` (half-open, see
/// core::AABB::contains) are returned, so blocks tiling space evaluate each contact once.
class ContactDetector {
public:
    explicit ContactDetector(DetectorConfig config = {});

    /// Replaces `out` with the contacts of `particles` (masters and shadows) among themselves
    /// and with `walls`, in canonical order (uid(i) < uid(j)). Not collective.
    void detect(ParticleStorage const& particles, WallList const& walls,
                core::AABB const& evaluationRegion, ContactList& out);

    /// The storage indices of the last `detect` in linked-cell order, small spheres first,
    /// then the large ones: a permutation for ParticleStorage::permute that puts neighbours
    /// next to each other in memory. Valid until the storage changes.
    [[nodiscard]] std::vector<std::size_t> spatialOrder() const;

    [[nodiscard]] DetectorStats const& stats() const { return m_stats; }
    [[nodiscard]] DetectorConfig const& config() const { return m_config; }
    /// Heap bytes of the reusable work arrays.
    [[nodiscard]] std::size_t bytes() const;

private:
    double largeThreshold(ParticleStorage const& particles);
    void largePass(ParticleStorage const& particles, core::AABB const& region, ContactList& out);
    void wallPass(ParticleStorage const& particles, WallList const& walls, core::AABB const& region,
                  ContactList& out);

    DetectorConfig m_config;
    DetectorStats m_stats;
    LinkedCells m_cells;
    std::vector<std::size_t> m_small;
    std::vector<std::size_t> m_large;
    std::vector<double> m_scratch;
};

} // namespace regolith::particles
