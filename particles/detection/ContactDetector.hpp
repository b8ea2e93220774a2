#pragma once
/// Contact detection for one block that stays O(N) for strongly polydisperse scenes: linked
/// cells sized for the small grains, plus a separate pass for the few large ones.
#include "core/math/AABB.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/DetectorConfig.hpp"
#include "particles/detection/LinkedCells.hpp"
#include "particles/detection/LocalPositions.hpp"
#include "particles/detection/OverlapScreen.hpp"
#include "particles/detection/PairCallbacks.hpp"
#include "particles/detection/PairOwnership.hpp"
#include "particles/detection/PairRule.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/detection/ReferenceDepths.hpp"
#include "particles/detection/SpringCarry.hpp"
#include "particles/detection/VerletList.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

namespace regolith::particles {

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
/// one cell size for all would give a radius-30 sphere among radius-0.4 grains cells of edge 60
/// (~10^5 grains each, O(N^2) work). Here a small sphere costs O(1) and a large one the cells in
/// its ball, which as many small grains could fill: O(N) in the grains the scene could hold, the
/// two-level case of the multilevel grids of Ogarko & Luding (Comput. Phys. Commun. 183 (2012)
/// 931). Pairs of two Fixed spheres are skipped (neither can move).
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
/// point if it lies strictly between the two centres (r_i - delta/2 > 0 and r_j - delta/2 > 0),
/// else -- the overlap reaches the smaller diameter, and the contact point lies behind the
/// smaller centre, where an open domain face may cut it off from every block -- the centre of
/// the smaller sphere (ties: j), in i's canonical frame. Either way q is strictly inside both
/// balls and inside the domain (a master's centre is), so some block contains q and holds both
/// copies (ParticleSync's overlap margin covers rounding).
/// With (w, o) = frame.wrap(q), the copy pair is emitted iff image(i) == -o (q seen from this copy
/// of i lies in the domain image the block tiles) and `evaluationRegion` (half-open,
/// core::AABB::contains) contains w. Among blocks tiling the domain, and among the several image
/// instances of the pair inside one block, one instance is therefore emitted, once. Without
/// periodic axes this is region.contains(q).
///
/// Verlet list. With a skin (DetectorConfig), `detect` on a mutable storage lists the
/// candidates with the reach r_a + r_b + skin (VerletList) and later tests only the listed
/// pairs, with the decision above: the same contacts as a full pass; of those, only the pairs
/// the copies' motion may have closed (VerletList::forEachNearPair). The list follows the
/// storage's changes through its trace; arrivals, and when it is rebuilt: ListRebuild.cpp,
/// docs/sync.md "Neighbour lists across sync calls".
///
/// A list that follows a drift (ListShift.cpp; docs/sync.md, "A list follows a drift"): where
/// the copies moved together, the references shift by their common drift instead of a
/// rebuild, the candidates stay, and only the pairs near a face and the parked ones are
/// settled again (the copies' depths along each axis against the drift along it).
///
/// A skin for the scene (DetectorConfig::widestRelativeSkin): a packing lists its first shell
/// with a wider skin at no cost per step and rebuilds less often; a gas keeps relativeSkin.
/// The contacts do not depend on it (SkinChoice.cpp).
///
/// Settled pairs and the fused loop. When a pair is listed (rebuild or arrival), the detector
/// decides once what the contact-point rule will answer for it while the list holds
/// (PairOwnership.hpp: the ownership point stays within skin/2 + |r_i - r_j|/2 of the pair's
/// reference midpoint): pairs some other block or image instance evaluates are dropped, pairs
/// this block evaluates whenever they overlap are stored in canonical order (PairMode::Owned),
/// and only pairs near a block or domain face keep the rule (PairMode::Check). Per step a
/// listed pair then costs the canonical distance test (PairRule.hpp, or OverlapScreen's lanes:
/// the same bits) and, with the callback overload of detect, its evaluation right away (one
/// loop, as LAMMPS's half list with shear history beside each pair). The contacts are the
/// same set as the full rule finds (tests/particles/VerletListTest.cpp).
///
/// Springs kept beside the list (DetectorConfig::keepSprings; KeptSprings.cpp, docs/sync.md
/// "Tangential springs beside the Verlet list"). A settled pair that cannot migrate, wrap or
/// change hands while the list holds (two masters deeper than skin / 2 inside the block, one
/// image instance) keeps its tangential spring beside the pair (PairMode::Kept,
/// VerletList::spring), as LAMMPS's fix neigh/history keeps its shear history. The grains'
/// histories lack them until writeBackSprings(), which the caller calls before anything reads
/// or changes the histories (a checkpoint, release(); countKeptContacts adds them to a count).
/// beforeSync writes back those a synchronisation moves; a rebuild carries the others over
/// (SpringCarry.cpp). Every step computes the same bits as with the histories.
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
    /// The mutable detect that also hands every pair contact it emits to `onPair(contact,
    /// hint)` at once (before the wall pass), `hint` being the pair's history slot hint
    /// (std::uint8_t&, for ContactHistory::touch) kept beside it in the Verlet list, so that
    /// detection and evaluation are one loop. The pair contacts are appended to `out` as well
    /// unless `keepPairs` is false (then out.pairs may stay empty: writing 96 bytes per
    /// contact and step is a tenth of the static lattice's CPU time); the wall contacts always
    /// are. Without a list (no skin) or with sortByUid, the contacts are handed over after the
    /// sort, in `out`'s order, with a fresh hint. A callback that takes `(PairOverlap const&,
    /// hint)` (TakesPairOverlaps) receives each contact as a PairOverlap instead, and computes
    /// the rest of the geometry itself. Not collective.
    template <class OnPair>
    void detect(ParticleStorage& particles, WallList const& walls,
                core::AABB const& evaluationRegion, PeriodicFrame const& frame, ContactList& out,
                OnPair&& onPair, bool keepPairs = true);
    /// The same without periodicity (default PeriodicFrame).
    void detect(ParticleStorage const& particles, WallList const& walls,
                core::AABB const& evaluationRegion, ContactList& out) {
        detect(particles, walls, evaluationRegion, PeriodicFrame{}, out);
    }
    void detect(ParticleStorage& particles, WallList const& walls,
                core::AABB const& evaluationRegion, ContactList& out) {
        detect(particles, walls, evaluationRegion, PeriodicFrame{}, out);
    }

    /// Tells the next mutable detect that no copy moved more than `distance` since the
    /// previous one (the integrator's largest move, DemStep::step), so that the Verlet list
    /// need not compare every position with its reference (VerletList::movedTooFar). Without
    /// a note the positions are compared. The bound must hold, or contacts go missing.
    void noteMotion(double distance) { m_movedAtMost = distance; }

    /// Where the Verlet list stands before the next mutable detect (prepareList).
    struct ListOutlook {
        bool due = false;     ///< that detect rebuilds the list (the rules of the class comment)
        bool halfway = false; ///< due, or some copy moved half the way to a rebuild
    };
    /// Optional, between noteMotion and the next mutable detect on `particles` (the same
    /// region and frame): follows the storage's changes and decides whether that detect
    /// rebuilds the list; rebuildNext() makes it rebuild in any case. So that the ranks rebuild
    /// in the same step (DemStep): a rank that rebuilds alone keeps the others waiting.
    /// Without a list (no skin, sortByUid): {false, false}. Not collective. Without
    /// `halfwayNeeded` (no list can come due on any rank) the positions are compared only
    /// where the bound reaches the whole budget, as in updateList.
    ListOutlook prepareList(ParticleStorage& particles, core::AABB const& evaluationRegion,
                            PeriodicFrame const& frame, bool halfwayNeeded = true);
    /// After prepareList: the next detect rebuilds the list (the contacts are the same).
    void rebuildNext() { m_rebuildDue = m_prepared; }
    /// The largest bound for the next noteMotion under which the next prepareList on
    /// `particles` (the same region and frame) cannot find the list due, provided the storage
    /// does not change before it: every copy then stays within the skin's budget
    /// (VerletList::quietMotion). -inf if it may come due whatever the motion (a change since
    /// the last detect, another region), +inf if there is no list to rebuild. So that the
    /// ranks need not agree on rebuilds in a step no list can come due (DemStep). Not
    /// collective.
    [[nodiscard]] double quietMotion(ParticleStorage const& particles,
                                     core::AABB const& evaluationRegion,
                                     PeriodicFrame const& frame) const;

    /// Before a synchronisation after which noteMotion(movedAtMost) will be called (the
    /// masters moved, and do not move in it): where a copy may then have moved skin / 2 from
    /// its reference, compares the masters with their references, and if one moved skin / 2,
    /// writes back to the histories of `particles` the kept springs of the pairs with a copy
    /// outside the region of the last detect, which must be the block's box: the
    /// synchronisation migrates or wraps those masters. The next detect shifts the list or
    /// rebuilds it ("A list that follows a drift"). Not collective.
    void beforeSync(ParticleStorage& particles, double movedAtMost);
    /// Writes the kept springs (see "Springs kept beside the list") to their grains' histories
    /// in `particles` (the storage of the last detect, unchanged since): an entry that exists is
    /// overwritten, one that does not is added if the last pass touched it (an older one is a
    /// broken contact, which ContactHistory::touch would restart, and which the history may
    /// have pruned since). The next detect fills them again. Not collective.
    void writeBackSprings(ParticleStorage& particles);
    /// Adds one to `perCopy[i]` for each kept spring of copy i (the pair's grain that holds its
    /// history) that the last pass touched, while the springs are kept beside the list: the
    /// contacts those grains' histories lack until writeBackSprings. Not collective.
    void countKeptContacts(std::span<std::uint32_t> perCopy) const;

    /// The storage indices of the last `detect` in linked-cell order, small spheres first,
    /// then the large ones: a permutation for ParticleStorage::permute that puts neighbours
    /// next to each other in memory. Valid until the storage changes.
    [[nodiscard]] std::vector<std::size_t> spatialOrder() const;

    [[nodiscard]] DetectorStats const& stats() const { return m_stats; }
    /// The Verlet skin of the last list rebuild [length]; 0 if none was built (no skin).
    [[nodiscard]] double listSkin() const { return m_listSkin; }
    [[nodiscard]] DetectorConfig const& config() const { return m_config; }
    /// Frees every work array and the neighbour list (the next detect starts afresh). Throws
    /// core::Error if kept springs were not written back.
    void release();
    /// Heap bytes of the reusable work arrays.
    [[nodiscard]] std::size_t bytes() const;

private:
    [[nodiscard]] bool listed() const { return m_config.skin > 0.0 || m_config.relativeSkin > 0.0; }
    /// Follows the storage's changes, adds the arrivals' pairs or rebuilds the list (as
    /// prepareList decided, if it was called).
    void updateList(ParticleStorage& particles, core::AABB const& region,
                    PeriodicFrame const& frame);
    /// Whether the list was built for `region` and `frame` (its settled pairs hold for them).
    [[nodiscard]] bool listedFor(core::AABB const& region, PeriodicFrame const& frame) const;
    /// Whether the copies that arrived since the list's rebuild are too many to add one by one.
    [[nodiscard]] bool tooManyArrivals() const;
    /// updateList's decision: follows the storage, adds the arrivals' pairs, sets m_rebuildDue;
    /// the positions are compared from `share` x the skin budget on (VerletList::movedTooFar).
    void decideRebuild(ParticleStorage& particles, core::AABB const& region,
                       PeriodicFrame const& frame, double share);
    /// prepareList's "halfway": a copy moved this share of the way to a rebuild.
    static constexpr double kHalfway = 0.5;
    /// Settles the listed pairs from the `first`-th on (see the class comment).
    void classifyListed(ParticleStorage const& particles, core::AABB const& region,
                        PeriodicFrame const& frame, std::size_t first);
    /// The per-step loop over the listed pairs: appends the contacts this block evaluates to
    /// `out` and calls onPair on each.
    template <class OnPair>
    void listedPass(ParticleStorage const& particles, core::AABB const& region,
                    PeriodicFrame const& frame, ContactList& out, OnPair&& onPair, bool keepPairs);

    double largeThreshold(ParticleStorage const& particles);
    /// The positions binning uses (local: shifted by their images, if some image is not
    /// zero). Fills m_small, m_large, stats.
    LocalPositions classify(ParticleStorage const& particles, PeriodicFrame const& frame,
                            double& rSmallMax, double& scale);
    /// Bins the small spheres into m_cells with candidate reach r_a + r_b + slack + skin.
    LocalPositions bin(ParticleStorage const& particles, PeriodicFrame const& frame, double skin);
    /// Calls f(a, b) for the candidate pairs with a large sphere (reach as bin's).
    template <class F>
    void largePass(LocalPositions const& positions, ParticleStorage const& particles,
                   PeriodicFrame const& frame, double reachSlack, F&& f);
    void rebuildList(ParticleStorage& particles, core::AABB const& region,
                     PeriodicFrame const& frame);
    /// Whether the list's skin adapts to the scene, and the relative skin the next rebuilds
    /// take, from the cells binned with the widest (SkinChoice.cpp).
    [[nodiscard]] bool widens() const;
    [[nodiscard]] double chooseRelativeSkin(ParticleStorage const& particles,
                                            LocalPositions const& positions,
                                            double rSmallMax) const;
    /// Whether the copies ka, kb (canonical order, list ids a, b) of a pair this block
    /// evaluates whenever they overlap stay its only instance while the list holds: two
    /// masters at image zero deeper than the list's motion inside `region`, meeting through
    /// one image only. Those pairs keep their springs beside the list where the model allows
    /// (see "Springs kept beside the list"), and lead the list (VerletList::classifyFrom)
    /// whether it does or not, so that the order, and the bits, do not depend on it.
    [[nodiscard]] bool staysInBlock(ParticleStorage const& particles, std::size_t ka,
                                    std::size_t kb, VerletList::Id a, VerletList::Id b,
                                    core::AABB const& region, PeriodicFrame const& frame,
                                    double rounding) const;
    /// The depth (per axis, shifts counted) beyond which both copies of a pair of the rebuild's
    /// copies make settlePair emit it whenever it overlaps: past any listed pair's reach and
    /// motion.
    [[nodiscard]] double settledDepth(double rounding) const;
    /// Per id of a rebuild: a master at image zero, not fixed, deeper than settledDepth, so that
    /// every pair of two such copies stays in the block (classifyListed's shortcut of settlePair).
    [[nodiscard]] std::vector<std::uint8_t> deepMasters(ParticleStorage const& particles,
                                                        PeriodicFrame const& frame,
                                                        double rounding) const;
    /// The mode of that pair, `stays` staysInBlock's answer: Owned, or Kept or KeptPressed if
    /// it keeps its spring beside the list.
    [[nodiscard]] PairMode settledMode(ParticleStorage const& particles, std::size_t ka,
                                       std::size_t kb, VerletList::Id a, VerletList::Id b,
                                       bool stays, double rounding) const;
    /// Looks up the storage indices ka, kb of the listed ids a, b and puts both in canonical
    /// order (uid(ka) <= uid(kb)).
    void orderListed(ParticleStorage const& particles, VerletList::Id& a, VerletList::Id& b,
                     std::size_t& ka, std::size_t& kb, CopyImage& shift) const;
    /// The ownership reach of listed pair ka, kb (ownershipReach with the list's skin, the
    /// rounding widened by the pair's scale).
    [[nodiscard]] double listedReach(ParticleStorage const& particles, std::size_t ka,
                                     std::size_t kb, double rounding) const;
    /// How the contact-point rule stands for the listed pair of ids a, b (put in canonical
    /// order, with their storage indices ka, kb) while the list holds: never emits it
    /// (VerletList::kDrop), must decide every step (PairMode::Check), or emits it whenever the
    /// two overlap (staysInBlock and settledMode: the mode, and whether it stays in the block,
    /// which leads the list). The one rule by which the listing (classifyListed) and a shift
    /// (shiftList) settle a pair.
    [[nodiscard]] VerletList::Decision
    settlePair(ParticleStorage const& particles, VerletList::Id& a, VerletList::Id& b,
               CopyImage& shift, std::size_t& ka, std::size_t& kb, core::AABB const& region,
               PeriodicFrame const& frame, double rounding) const;
    /// Writes a kept spring back to the history of copy i, for partner `partner` (whose entry
    /// fillKeptSprings found in slot `hint`).
    void writeBackSpring(ParticleStorage& particles, std::size_t i, Uid partner,
                         KeptSpring const& kept, std::uint8_t hint) const;
    /// How far a centre may be from its reference while the list holds (+ `rounding`).
    [[nodiscard]] double listMotion(double rounding) const;
    /// Whether a listed pair of reach r_a + r_b cannot meet through a second periodic image
    /// while the list holds (which would share the spring, ContactHistory::touch's `again`).
    [[nodiscard]] bool oneImageInstance(double reach, PeriodicFrame const& frame,
                                        double rounding) const;
    /// Whether a listed pair whose reference centres stand sqrt(apart2) apart overlaps (reach
    /// r_a + r_b) while the list holds.
    [[nodiscard]] bool pressedWhileListed(double apart2, double reach, double rounding) const;
    /// Fills the kept springs of the pairs from the `first`-th on: from the springs carried
    /// over a rebuild (fillCarriedSprings; `first` 0), else from the histories.
    void fillKeptSprings(ParticleStorage& particles, std::size_t first);
    /// At a rebuild, before the restart: sets the live kept springs aside (SpringCarry.cpp).
    void carrySprings(ParticleStorage const& particles);
    /// After it: each kept pair of the new list takes its carried spring, or its history's.
    void fillCarriedSprings(ParticleStorage& particles);
    /// Writes the carried springs no pair took back to the histories.
    void writeBackCarried(ParticleStorage& particles);
    /// Writes back the kept springs of the pairs with a copy outside the list's region, which
    /// a synchronisation may move (they stay live beside the list too).
    void writeBackLeaving(ParticleStorage& particles);
    /// The spring of copy i's history for partner j as a kept one, and its slot in `hint`.
    [[nodiscard]] static KeptSpring springFromHistory(ParticleStorage const& particles,
                                                      std::size_t i, std::size_t j,
                                                      std::uint8_t& hint);
    /// Compares every copy with its reference and shifts the list where the copies, after
    /// `motion` more, could reach the budget but moved together (ListShift.cpp); the bound on
    /// their motion restarts from the comparison. Pre: the list follows the storage.
    void followDrift(ParticleStorage& particles, double motion);
    /// In decideRebuild, after the list followed the storage: followDrift if the step's
    /// motion `moved` once more could bring the list to its budget.
    void shiftAhead(ParticleStorage& particles, double moved);
    /// Shifts the list's references by `drift` (every copy within `spread` of its shifted
    /// reference) and settles its pairs again (ListShift.cpp).
    void shiftList(ParticleStorage& particles, core::Vec3 const& drift, double spread);
    /// The largest share of the budget a list's copies may spread over for it to shift.
    static constexpr double kShiftSpread = 0.9;
    /// Adds the pairs of the copies in m_fresh; false if one lies beyond m_listScale.
    bool addArrivals(ParticleStorage const& particles, core::AABB const& region,
                     PeriodicFrame const& frame);
    void wallPass(ParticleStorage const& particles, WallList const& walls, ContactList& out);
    /// Marks in `near` (one byte per copy, zeroed) every copy a plane of `walls` may touch
    /// (any copy if a wall is not a plane): wallPass's screen.
    static void screenPlaneWalls(ParticleStorage const& particles, std::span<Wall const> walls,
                                 std::vector<std::uint8_t>& near);
    void sortByUid(ParticleStorage const& particles, ContactList& out) const;

    DetectorConfig m_config;
    DetectorStats m_stats;
    LinkedCells m_cells;
    std::vector<std::uint32_t> m_small;   ///< while binning: 4 bytes per copy (nearly every one)
    std::vector<std::uint8_t> m_nearWall; ///< wallPass: the copies a wall may touch
    std::vector<std::size_t> m_large;
    std::vector<double> m_scratch;
    VerletList m_list;
    std::vector<std::size_t> m_fresh;        ///< storage indices of the copies that just arrived
    std::vector<VerletList::Id> m_largeIds;  ///< the large spheres of the last rebuild
    std::vector<double> m_arrivalLanes;      ///< addArrivals: the arrivals' x, y, z and radii
    std::vector<std::uint8_t> m_arrivalHits; ///< addArrivals: which of them a fresh copy reaches
    ReferenceDepths m_depths;                ///< of the last rebuild's copies, and the shifts since
    /// shiftList: per id of the rebuild, whether it lies deeper than settledDepth (1 or 0).
    std::vector<std::uint8_t> m_deepIds;
    double m_builtRadiusMin = 0.0, m_builtRadiusMax = 0.0; ///< the rebuild's copies' radii
    double m_listScale = 0.0; ///< coordinate scale of the last rebuild (its slack)
    double m_listSkin = 0.0;
    double m_relativeSkin = 0.0;  ///< chosen for the scene (0: not yet; "A skin for the scene")
    std::uint32_t m_rebuilds = 0; ///< list rebuilds so far (every 16th chooses the skin)
    std::uint32_t m_shifts = 0;   ///< list shifts since the last detect (DetectorStats)
    /// The copies spread too far apart for the list to shift (a gas): it is rebuilt as before.
    bool m_spreadOut = false;
    double m_movedAtMost = std::numeric_limits<double>::infinity(); ///< noteMotion, one detect
    bool m_prepared = false;        ///< prepareList decided for the next detect
    bool m_rebuildDue = false;      ///< the next (or this) detect rebuilds the list
    std::size_t m_listedBefore = 0; ///< pairs listed before this detect's arrivals
    core::AABB m_listRegion;        ///< the region the list's pairs were settled for
    PeriodicFrame m_listFrame;      ///< and the frame
    bool m_springsLive = false;     ///< the kept springs hold what the histories lack
    CarriedSprings m_carried;       ///< over the last rebuild, until the fill (carrySprings)
    std::size_t m_fillFrom = 0;     ///< the first pair whose kept spring the next pass fills
    std::uint32_t m_pass = 0;       ///< the pass of the last detect that kept springs
};

} // namespace regolith::particles

// The fused detect and its pass over the listed pairs (member templates).
#include "particles/detection/FusedDetect.hpp"
