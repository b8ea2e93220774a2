#pragma once
/// Contact detection for one block that stays O(N) for strongly polydisperse scenes: linked
/// cells sized for the small grains, plus a separate pass for the few large ones.
#include "core/math/AABB.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/LinkedCells.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/detection/VerletList.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace regolith::particles {

struct DetectorConfig {
    /// Verlet skin [length]: with skin > 0 (or relativeSkin > 0), detect() on a mutable
    /// storage keeps a neighbour list of the pairs closer than r_a + r_b + skin and reuses it
    /// until some copy moved skin / 2 (see ContactDetector). 0: linked cells every call.
    double skin = 0.0;
    /// If skin is 0: skin = relativeSkin * (the largest small radius) at every rebuild.
    double relativeSkin = 0.0;
    /// Spheres with a radius above this go to the large pass [length]; 0 = automatic:
    /// `largeFactor` times the median radius of the block's spheres.
    double largeRadius = 0.0;
    double largeFactor = 2.0;
    /// The cell grid has at most this many cells per small sphere (the edge grows otherwise).
    std::size_t maxCellsPerSphere = 8;
    /// Sort the output by (uid_i, uid_j, image(j) - image(i)) and (uid, wall), so that forces
    /// are summed in an order independent of storage order (reproducible mode). Costs
    /// O(C log C).
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
    /// Overlaps (Fixed pairs too) before the ownership rule, every image instance counted.
    std::size_t overlapsFound = 0;
    /// Spread of the candidate tests beyond r_a + r_b, against rounding of local positions.
    double slack = 0.0;
    /// Verlet list (mutable detect with a skin): the skin of the last rebuild, whether this
    /// call rebuilt, the pairs listed, the copies that arrived since the last rebuild and
    /// were added to the list in this call.
    double skin = 0.0;
    bool rebuilt = false;
    std::size_t listedPairs = 0;
    std::size_t arrivals = 0;
};

/// A region "this block evaluates contacts whose ownership point lies in [min, max)" that
/// contains every point: for a single block.
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
/// Periodic copies. Each stored copy has its master's canonical position x and an image k
/// (CopyImage.hpp); binning and the candidate search use local positions x + k * period
/// (copied to a scratch array only if some image is non-zero), with a slack of a few ulps of
/// the coordinates so that rounding there can only add candidates. Whether a candidate pair
/// overlaps is then decided in the CANONICAL frame of i (lower uid): shiftJ =
/// imageOffset(k_j - k_i), d = (x_j + shiftJ) - x_i, overlap iff |d| < r_i + r_j; normal,
/// penetration and point follow from d (Contact.hpp). These bits depend on the two canonical
/// states and the image difference only, so every block that sees the pair, at any image,
/// finds the same contact. A grain's contact with its own periodic image (possible only for a
/// grain wider than the period) is ignored.
///
/// Contact-point rule (which block evaluates a pair). The ownership point q is the contact
/// point if it lies strictly inside both balls (|point - x_i| < r_i and |point - (x_j +
/// shiftJ)| < r_j), else -- one sphere has swallowed the other's centre -- the centre of the
/// smaller sphere (ties: j), in i's canonical frame. Either way q is strictly inside both balls,
/// so the block containing q holds both copies (ParticleSync's overlap margin covers rounding).
/// With (w, o) = frame.wrap(q), the copy pair is emitted iff image(i) == -o (q seen from this copy
/// of i lies in the domain image the block tiles) and `evaluationRegion` (half-open,
/// core::AABB::contains) contains w. Among blocks tiling the domain, and among the several image
/// instances of the pair inside one block, one instance is therefore emitted, once. Without
/// periodic axes this is region.contains(q).
///
/// Verlet list. With a skin (DetectorConfig), `detect` on a mutable storage builds the same
/// candidates with the reach r_a + r_b + skin into a VerletList and, in later calls, tests only
/// the listed pairs (the contact decision above is unchanged, so the contacts are the same
/// set). The list follows the storage's changes through its trace (VerletList.hpp): a copy
/// that arrived since the last call is tested against the cells of the last rebuild (which
/// hold the reference positions), the large spheres and the other arrivals, with the same
/// reach. It is rebuilt when some copy moved skin / 2 since its reference time, when the
/// trace broke (permute, clear, a radius changed), when the arrivals exceed 1/16 of the copies
/// (plus 64), or when an arrival lies beyond the coordinate scale of the last rebuild (its
/// rounding slack).
///
/// Wall rule. Walls are global and not periodic, so a sphere-wall contact is decided by the
/// sphere's canonical centre: it is emitted only for the master copy (Shadow flag clear, image
/// zero), which exists in exactly one block. (The contact point lies behind the wall, outside
/// every block for a wall on a domain face, so it cannot decide.) `evaluationRegion` does not
/// filter wall contacts.
class ContactDetector {
public:
    explicit ContactDetector(DetectorConfig config = {});

    /// Replaces `out` with the contacts of `particles` (masters and shadows, at any periodic
    /// image) among themselves and with `walls` that this block evaluates (see the class
    /// comment), in canonical order (uid(i) < uid(j)). `evaluationRegion` is the block's box
    /// in domain coordinates. Throws core::Error if a copy has a non-zero image on an axis
    /// that is not periodic in `frame`. Not collective.
    void detect(ParticleStorage const& particles, WallList const& walls,
                core::AABB const& evaluationRegion, PeriodicFrame const& frame, ContactList& out);
    /// The same; with a skin configured, through the Verlet list (see the class comment),
    /// which starts tracing `particles` (ParticleStorage::startTracing) and keeps following
    /// it. Without a skin, as the const overload.
    void detect(ParticleStorage& particles, WallList const& walls,
                core::AABB const& evaluationRegion, PeriodicFrame const& frame, ContactList& out);
    /// The same without periodicity (default PeriodicFrame).
    void detect(ParticleStorage const& particles, WallList const& walls,
                core::AABB const& evaluationRegion, ContactList& out) {
        detect(particles, walls, evaluationRegion, PeriodicFrame{}, out);
    }
    void detect(ParticleStorage& particles, WallList const& walls,
                core::AABB const& evaluationRegion, ContactList& out) {
        detect(particles, walls, evaluationRegion, PeriodicFrame{}, out);
    }

    /// The storage indices of the last `detect` in linked-cell order, small spheres first,
    /// then the large ones: a permutation for ParticleStorage::permute that puts neighbours
    /// next to each other in memory. Valid until the storage changes.
    [[nodiscard]] std::vector<std::size_t> spatialOrder() const;

    [[nodiscard]] DetectorStats const& stats() const { return m_stats; }
    [[nodiscard]] DetectorConfig const& config() const { return m_config; }
    /// Frees every work array and the neighbour list (the next detect starts afresh).
    void release();
    /// Heap bytes of the reusable work arrays.
    [[nodiscard]] std::size_t bytes() const;

private:
    class PairRule;

    double largeThreshold(ParticleStorage const& particles);
    /// The positions binning uses: ps.positions() or m_local. Fills m_small, m_large, stats.
    std::span<core::Vec3 const> classify(ParticleStorage const& particles,
                                         PeriodicFrame const& frame, double& rSmallMax,
                                         double& scale);
    /// Bins the small spheres into m_cells with candidate reach r_a + r_b + slack + skin.
    std::span<core::Vec3 const> bin(ParticleStorage const& particles, PeriodicFrame const& frame,
                                    double skin);
    /// Calls f(a, b) for the candidate pairs with a large sphere (reach as bin's).
    template <class F>
    void largePass(std::span<core::Vec3 const> positions, ParticleStorage const& particles,
                   double reachSlack, F&& f);
    void rebuildList(ParticleStorage& particles, PeriodicFrame const& frame);
    /// Adds the pairs of the copies in m_fresh; false if one lies beyond m_listScale.
    bool addArrivals(ParticleStorage const& particles, PeriodicFrame const& frame);
    void wallPass(ParticleStorage const& particles, WallList const& walls, ContactList& out);
    void sortByUid(ParticleStorage const& particles, ContactList& out) const;

    DetectorConfig m_config;
    DetectorStats m_stats;
    LinkedCells m_cells;
    std::vector<std::size_t> m_small;
    std::vector<std::size_t> m_large;
    std::vector<double> m_scratch;
    std::vector<core::Vec3> m_local; ///< local positions, when some image is non-zero
    VerletList m_list;
    std::vector<std::size_t> m_fresh;       ///< storage indices of the copies that just arrived
    std::vector<VerletList::Id> m_largeIds; ///< the large spheres of the last rebuild
    double m_listScale = 0.0;               ///< coordinate scale of the last rebuild (its slack)
    double m_listSkin = 0.0;
};

} // namespace regolith::particles
