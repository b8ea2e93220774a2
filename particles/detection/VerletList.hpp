#pragma once
/// A Verlet neighbour list (Verlet, Phys. Rev. 159 (1967) 98; Allen & Tildesley, "Computer
/// Simulation of Liquids", 2nd ed., sec. 5.3.1) over the copies of one ParticleStorage that
/// survives the storage's changes between steps: the synchronisation adds and removes copies
/// every step (shadows appearing, masters migrating), which moves other copies to new
/// indices, yet a rebuild costs as much as a linked-cell pass over everything.
///
/// How it follows the storage. The list names copies by an id, not an index: at a rebuild
/// id = index; the storage's trace (ParticleStorage::startTracing) carries each copy's id
/// along when a removal moves it, and journals the slots it wrote. follow() reads that
/// journal: the ids that were in written slots die unless they reappear in another written
/// slot; copies that arrived since (or were re-keyed to another periodic image) get a new id
/// and are reported "fresh", so that the caller can add their pairs. Work per step is
/// O(changes), never O(N), apart from the displacement check.
///
/// Validity. A pair of copies is in the list if their local positions at their reference
/// times (the rebuild, or the step a fresh copy arrived) were closer than r_a + r_b + skin
/// (+ the caller's rounding slack). As long as no copy moved skin / 2 or more from its
/// reference position (movedTooFar), every pair that overlaps now is therefore in the list.
/// A copy's image never changes under one id (setImage makes it fresh), so canonical
/// displacements equal local ones. shift() moves every reference by a common drift: the
/// pairs' distances change by the displacements less that drift, so the same argument holds
/// for the displacements from the moved references (ContactDetector, "A list that follows a
/// drift").
///
/// Reference positions are kept in single precision relative to an origin (12 bytes per id,
/// not 24): reference() is within referenceSlack() of the true reference position, so
/// movedTooFar tests skin / 2 - referenceSlack(), and users widen their own tests of
/// reference positions by it (a superset of pairs, the same contacts).
///
/// Beside each pair the list keeps its PairMode, a one-byte hint where its tangential spring
/// sat in its owner's ContactHistory last time (ContactHistory::touch), and for the pairs kept
/// the spring itself: the per-step loop neither repeats the rule nor searches the history.
#include "core/math/FloatBounds.hpp"
#include "core/math/Vec3.hpp"
#include "particles/detection/PairMode.hpp"
#include "particles/storage/ContactHistory.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace regolith::particles {

class VerletList {
public:
    using Id = std::uint32_t;
    static constexpr std::uint32_t kDead = std::numeric_limits<std::uint32_t>::max();
    /// Returned by a classifier (classifyFrom) to drop a pair from the list.
    static constexpr int kDrop = -1;
    /// The most pairs forEachNearBlock hands over at once.
    static constexpr std::size_t kBlock = 64;

    /// Starts a new, empty list over `ps` as it is now: id = index for every copy, reference
    /// positions = current positions. The caller adds the pairs (addPair, ids = indices).
    void restart(ParticleStorage& ps, double skin);
    /// Forgets the list: the next follow() returns false.
    void invalidate() {
        m_storage = nullptr;
        m_live.stale = true;
    }

    /// A pair's gap not known: forEachNearPair always offers it.
    static constexpr float kNoGap = -std::numeric_limits<float>::infinity();
    /// `gap` as addPair takes it: in single precision, rounded down.
    [[nodiscard]] static float gapBelow(double gap) { return core::floatNotAbove(gap); }
    /// Adds a pair in mode Check (any order). `gap` [length]: a lower bound on how much farther
    /// apart than touching the two copies stand now (gapBelow), or kNoGap. `shift`: b's
    /// whole periods from a beyond the copies' images, on the axes where the cells wrap
    /// (PeriodicFrame::wrapped): b stands at its local position + shift * period from a.
    void addPair(Id a, Id b, float gap = kNoGap, CopyImage const& shift = kNoImage) {
        m_live.stale = true;
        m_pairs.push_back({a, b});
        m_shift.push_back(shift);
        m_mode.push_back(PairMode::Check);
        m_hint.push_back(0);
        m_gap.push_back(gap);
        m_apart += gap >= kApart * static_cast<float>(m_skin) ? 1 : 0;
    }
    /// A classifier's answer (classifyFrom): the pair's mode (a PairMode as int) or kDrop, and
    /// whether the pair leads the list.
    struct Decision {
        int mode = kDrop;
        bool leads = false;
    };
    /// Calls `decide(a, b, shift)` (by reference: it may swap a and b, and then negates the
    /// shift; returns a Decision) for every
    /// pair from the `first`-th on, keeps the pair with the mode decided or parks it (kDrop:
    /// out of the per-step loop, but decided again by resettle). The pairs kept from the
    /// `first`-th on are ordered: those that lead first, then the others, each in the order
    /// added. (The caller lets the pairs that keep their springs lead, so that the per-step
    /// loop meets runs of one kind: whether a pair keeps its spring is a branch per overlapping
    /// pair there, mispredicted where kinds alternate, as near scene B's periodic faces.) A pair
    /// that keeps its spring (keepsSpring) gets a slot, spring(p), for the caller to fill.
    template <class D>
    void classifyFrom(std::size_t first, D&& decide) {
        std::size_t out = first;
        m_trailing.clear();
        m_live.stale = m_live.stale || first < m_pairs.size();
        auto const put = [&](std::array<Id, 2> const& pair, CopyImage const& shift, float gap,
                             PairMode mode) {
            m_pairs[out] = pair;
            m_shift[out] = shift;
            m_gap[out] = gap;
            m_mode[out] = mode;
            m_hint[out] = 0;
            ++out;
        };
        for (std::size_t p = first; p < m_pairs.size(); ++p) {
            auto pair = m_pairs[p];
            CopyImage shift = m_shift[p];
            Decision const decided = decide(pair[0], pair[1], shift);
            if (decided.mode == kDrop) {
                m_parked.push_back({pair, shift});
                continue;
            }
            auto const mode = static_cast<PairMode>(decided.mode);
            m_owned += mode != PairMode::Check ? 1 : 0;
            m_kept += keepsSpring(mode) ? 1 : 0;
            m_pressed += isPressed(mode) ? 1 : 0;
            if (decided.leads)
                put(pair, shift, m_gap[p], mode);
            else
                m_trailing.push_back({pair, shift, m_gap[p], mode});
        }
        for (TrailingPair const& t : m_trailing)
            put(t.pair, t.shift, t.gap, t.mode);
        m_pairs.resize(out);
        m_shift.resize(out);
        m_gap.resize(out);
        m_mode.resize(out);
        m_hint.resize(out);
        if (m_kept != 0) // parallel to the pairs once one is kept (most lists keep none)
            m_springs.resize(out);
    }

    /// After shift(): calls `decide(a, b, shift, listed, was, spring, hint)` for every pair whose
    /// two copies live, the listed ones first unless `unchanged(a, b)` (listed = true, `was` their
    /// mode, `spring` and `hint` theirs, in place), then the parked ones (listed = false,
    /// PairMode::Check, an empty spring, hint 0), and lists each with the mode returned and
    /// `spring` and `hint` as `decide` left them (a listed pair in its place, a parked one
    /// appended), or parks it (kDrop; a listed pair leaves a hole). Defined beside its one
    /// user, ContactDetector's shiftList (ListShift.cpp).
    template <class S, class D>
    void resettle(S&& unchanged, D&& decide);

    /// Catches up with the storage's changes since the last restart or follow (see the class
    /// comment). Returns false if the list cannot follow: never restarted, another storage
    /// or trace, or a broken trace (permute, clear, a radius changed). Otherwise every copy
    /// has an id afterwards, and `fresh` receives the storage indices of the copies that got
    /// one now (their pairs are the caller's to add, addPair with idOf()). Not collective.
    bool follow(ParticleStorage& ps, std::vector<std::size_t>& fresh);
    /// Whether follow(ps) would find nothing to follow: the same storage and trace, whole, and
    /// no change since the last restart or follow.
    [[nodiscard]] bool followsUnchanged(ParticleStorage const& ps) const {
        return m_storage == &ps && ps.traceSession() == m_session && !ps.traceBroken() &&
               ps.traceJournal().empty();
    }

    /// Whether some copy may have moved skin / 2 or more from its reference position (or is
    /// not finite): the list may then miss a pair and must be rebuilt. `movedAtMost` bounds
    /// every copy's displacement since the last call (+inf if unknown): the bounds add up
    /// (triangle inequality), and only once their sum reaches skin / 2 are the positions
    /// compared, O(N), which resets the sum to the largest displacement found. With `share`
    /// < 1 they are compared once the sum reaches share x skin / 2 (so that moved() tells how
    /// far the list has used its skin). Pre: follow() true.
    [[nodiscard]] bool movedTooFar(ParticleStorage const& ps, double movedAtMost,
                                   double share = 1.0);
    /// Whether movedTooFar(ps, movedAtMost) would compare the positions: whether some copy
    /// may then be skin / 2 or more from its reference position.
    [[nodiscard]] bool mayMoveTooFar(double movedAtMost, double share = 1.0) const;
    /// Where the copies stand against their references: the largest distance, and the centre
    /// of the displacements' bounding box (the drift), all within referenceSlack().
    /// Pre: followsUnchanged(ps).
    struct Displacements {
        double largest = 0.0;
        double largestMaster = 0.0; ///< the largest distance of a master (Flags::isMaster)
        core::Vec3 drift = core::Vec3::Zero();
        bool finite = true;
    };
    [[nodiscard]] Displacements displacements(ParticleStorage const& ps) const;
    /// The radius of the ball about `drift` (displacements().drift) that holds every
    /// displacement: the spread, the largest distance from it. A second pass over the copies,
    /// taken only where the largest distance alone does not decide. Pre: as displacements().
    [[nodiscard]] double spread(ParticleStorage const& ps, core::Vec3 const& drift) const;
    /// Moves every reference by `drift` (the list's frame follows the copies' common motion):
    /// the pairs listed stay a superset of the overlapping ones as long as no copy moves the
    /// budget from its moved reference, because a pair's distance changes by at most the sum
    /// of the two displacements less any common drift. `moved` becomes the bound on every
    /// copy's distance from its moved reference (spread()). The caller settles the pairs
    /// again (resettle): what was decided from the old references may not hold.
    void shift(core::Vec3 const& drift, double moved);
    /// The references' total shift since the last restart (the cells of that rebuild hold the
    /// copies where they were then) [length].
    [[nodiscard]] core::Vec3 drift() const { return m_origin - m_builtOrigin; }
    /// The copies' common displacement from their references, as last measured
    /// (displacements().drift, less the shifts since): a copy that arrives is referenced
    /// there, not where it stands, so that it moves with the others.
    void setCommonDisplacement(core::Vec3 const& common) { m_common = common; }
    /// Sets the bound on every copy's distance from its reference to `moved` (measured:
    /// displacements()) plus the reference slack.
    void setMoved(double moved) { m_moved = moved + m_referenceSlack; }

    /// The largest `movedAtMost` for which the next movedTooFar(ps, movedAtMost, share) is
    /// false at any share, if the bound holds: mayMoveTooFar(movedAtMost) is false, so every
    /// copy stays within the budget, whether the positions are compared or not. A relative
    /// 1e-6 of the budget below the exact limit (the rounding of the sums); -inf if no bound
    /// is small enough.
    [[nodiscard]] double quietMotion() const;
    /// The bound on every copy's distance from its reference after the last movedTooFar (the
    /// largest distance found if it compared the positions) [length].
    [[nodiscard]] double moved() const { return m_moved; }
    /// The distance at which movedTooFar reports a rebuild: skin / 2 less the reference slack.
    [[nodiscard]] double budget() const { return 0.5 * m_skin - m_referenceSlack; }

    [[nodiscard]] static Id idOf(ParticleStorage const& ps, std::size_t index) {
        return ps.traceTag(index);
    }
    /// Storage index of a live id, or kDead.
    [[nodiscard]] std::uint32_t indexOf(Id id) const { return m_indexOf[id]; }
    /// Canonical position of `id` at its reference time [length], within referenceSlack().
    [[nodiscard]] core::Vec3 reference(Id id) const {
        Reference const& r = m_reference[id];
        return m_origin + core::Vec3(double{r[0]}, double{r[1]}, double{r[2]});
    }
    /// reference(id) less drift(): where id's reference stood before the shifts since the last
    /// restart, within referenceSlack() [length].
    [[nodiscard]] core::Vec3 unshiftedReference(Id id) const {
        Reference const& r = m_reference[id];
        return m_builtOrigin + core::Vec3(double{r[0]}, double{r[1]}, double{r[2]});
    }
    /// Bound on |reference(id) - the position it stands for| over all ids [length]: the
    /// rounding to float of coordinates up to m_extent from the origin, and of the two
    /// double operations around it.
    [[nodiscard]] double referenceSlack() const { return m_referenceSlack; }
    /// Ids given since the last restart (to copies that arrived), oldest first.
    [[nodiscard]] std::span<Id const> arrivals() const { return m_arrivals; }
    /// Copies at the last restart.
    [[nodiscard]] std::size_t builtSize() const { return m_built; }
    [[nodiscard]] double skin() const { return m_skin; }

    /// Calls f(a, b, p) with the storage indices of every pair from the `first`-th on whose
    /// two copies are alive and its position p in the list (for mode(p), hint(p), spring(p)),
    /// in the order the pairs were added.
    template <class F>
    void forEachPair(F&& f, std::size_t first = 0) const {
        for (std::size_t p = first; p < m_pairs.size(); ++p)
            visitLive(p, f);
    }
    /// forEachPair over the pairs whose mode keeps a spring: the mode is read first, the
    /// copies' indices only for those.
    template <class F>
    void forEachKeptPair(F&& f, std::size_t first = 0) const {
        for (std::size_t p = first; p < m_pairs.size(); ++p)
            if (keepsSpring(m_mode[p]))
                visitLive(p, f);
    }
    /// forEachPair over the pairs whose gap (addPair) is below twice moved() (+ the reference
    /// slack): the others cannot have closed it. Same pairs overlapping, same order.
    template <class F>
    void forEachNearPair(F&& f) const {
        forEachNearBlock([&](std::uint32_t const* a, std::uint32_t const* b, std::uint32_t const* p,
                             std::size_t n) {
            for (std::size_t k = 0; k < n; ++k)
                f(std::size_t{a[k]}, std::size_t{b[k]}, std::size_t{p[k]});
        });
    }
    /// forEachNearPair's pairs a block at a time: calls f(a, b, p, n) with the storage indices
    /// a[k], b[k] and list positions p[k], k < n <= kBlock, of the next n live near pairs, in
    /// order; every block but the last holds kBlock. A list with few pairs far apart (a
    /// packing's first shell) offers every pair, their indices looked up again only after the
    /// pairs or the storage's layout changed (refreshLive). Else the near ones of each stretch
    /// are picked by their gaps without a branch per pair (near or not is a coin toss as the
    /// list ages), and only those looked up (a gas's list is mostly pairs far apart).
    template <class F>
    void forEachNearBlock(F&& f) const {
        if (m_apart * kFewApart < m_pairs.size()) {
            if (m_live.stale)
                refreshLive();
            std::size_t const n = m_live.a.size();
            for (std::size_t first = 0; first < n; first += kBlock)
                f(m_live.a.data() + first, m_live.b.data() + first, m_live.at.data() + first,
                  std::min(kBlock, n - first));
            return;
        }
        float const reach = nearReach();
        std::size_t const n = m_pairs.size();
        std::array<std::uint32_t, kBlock> near;
        std::array<std::uint32_t, 2 * kBlock> a, b, at; // a block, and what the next stretch adds
        std::size_t count = 0;
        for (std::size_t first = 0; first < n; first += kBlock) {
            std::size_t const m = std::min(kBlock, n - first);
            std::size_t nearCount = 0;
            for (std::size_t q = 0; q < m; ++q) {
                near[nearCount] = static_cast<std::uint32_t>(first + q);
                nearCount += !(m_gap[first + q] >= reach) ? 1 : 0; // NaN: near
            }
            for (std::size_t h = 0; h < nearCount; ++h) {
                std::size_t const p = near[h];
                std::uint32_t const ka = m_indexOf[m_pairs[p][0]], kb = m_indexOf[m_pairs[p][1]];
                if (ka == kDead || kb == kDead) [[unlikely]]
                    continue; // (a copy left since the rebuild: rare, a branch predicted)
                a[count] = ka;
                b[count] = kb;
                at[count] = static_cast<std::uint32_t>(p);
                ++count;
            }
            if (count >= kBlock) {
                f(a.data(), b.data(), at.data(), kBlock);
                count -= kBlock;
                std::copy_n(a.data() + kBlock, count, a.data());
                std::copy_n(b.data() + kBlock, count, b.data());
                std::copy_n(at.data() + kBlock, count, at.data());
            }
        }
        if (count != 0)
            f(a.data(), b.data(), at.data(), count);
    }
    [[nodiscard]] PairMode mode(std::size_t p) const { return m_mode[p]; }
    /// Pair p's shift (addPair).
    [[nodiscard]] CopyImage const& shift(std::size_t p) const { return m_shift[p]; }
    /// Every pair's shift, by position.
    [[nodiscard]] std::span<CopyImage const> shifts() const { return m_shift; }
    /// Every pair's mode, hint and kept spring (empty while none is kept), by position: for
    /// a loop whose stores the compiler cannot tell apart from the list's own.
    [[nodiscard]] std::span<PairMode const> modes() const { return m_mode; }
    [[nodiscard]] std::span<std::uint8_t> hints() { return m_hint; }
    [[nodiscard]] std::span<KeptSpring> springs() { return m_springs; }
    /// Pair p's history slot hint (ContactHistory::touch).
    [[nodiscard]] std::uint8_t& hint(std::size_t p) { return m_hint[p]; }
    [[nodiscard]] std::uint8_t hint(std::size_t p) const { return m_hint[p]; }
    /// A kept pair's tangential spring, with its stamp as ContactHistory's.
    [[nodiscard]] KeptSpring& spring(std::size_t p) { return m_springs[p]; }
    [[nodiscard]] KeptSpring const& spring(std::size_t p) const { return m_springs[p]; }
    [[nodiscard]] std::size_t numPairs() const { return m_pairs.size(); }
    /// Pairs classified PairMode::Owned, Kept or KeptPressed since the last restart.
    [[nodiscard]] std::size_t numOwned() const { return m_owned; }
    /// Pairs classified PairMode::Kept or KeptPressed since the last restart.
    [[nodiscard]] std::size_t numKept() const { return m_kept; }
    /// Pairs classified PairMode::KeptPressed since the last restart.
    [[nodiscard]] std::size_t numPressed() const { return m_pressed; }
    /// Heap bytes held.
    [[nodiscard]] std::size_t bytes() const;

private:
    /// f(a, b, p) with pair p's storage indices, if both copies are alive.
    template <class F>
    void visitLive(std::size_t p, F& f) const {
        std::uint32_t const a = m_indexOf[m_pairs[p][0]], b = m_indexOf[m_pairs[p][1]];
        if (a != kDead && b != kDead)
            f(std::size_t{a}, std::size_t{b}, p);
    }
    /// The live pairs' storage indices and list positions, in list order: forEachNearBlock's
    /// walk over every pair, looked up again (refreshLive) after anything changed the pairs or
    /// the ids' indices.
    struct LivePairs {
        std::vector<std::uint32_t> a, b, at;
        bool stale = true;
    };
    void refreshLive() const;
    mutable LivePairs m_live;
    ParticleStorage const* m_storage = nullptr;
    std::uint64_t m_session = 0;
    double m_skin = 0.0;
    double m_moved = 0.0; ///< bound on every copy's distance from its reference (movedTooFar)
    std::size_t m_built = 0;
    std::size_t m_owned = 0;
    std::size_t m_kept = 0;
    std::size_t m_pressed = 0;
    std::vector<std::array<Id, 2>> m_pairs;
    std::vector<CopyImage> m_shift; ///< per pair: addPair's
    struct ParkedPair {
        std::array<Id, 2> pair;
        CopyImage shift;
    };
    std::vector<ParkedPair> m_parked;      ///< pairs dropped from the loop (classifyFrom)
    std::vector<ParkedPair> m_parkedAgain; ///< resettle's, swapped with m_parked
    Id m_hole = 0; ///< an id that is never alive (a parked pair's place in m_pairs names it)
    std::vector<float> m_gap; ///< per pair: addPair's (forEachNearPair)
    /// Pairs listed since the restart with a gap of kApart x skin or more (skipped for half the
    /// list's life at least); fewer than one in kFewApart: forEachNearPair offers every pair.
    std::size_t m_apart = 0;
    static constexpr float kApart = 0.25F;
    static constexpr std::size_t kFewApart = 4;
    /// forEachNearPair's bound on the gap a pair may have closed, rounded up.
    [[nodiscard]] float nearReach() const;
    struct TrailingPair {
        std::array<Id, 2> pair;
        CopyImage shift;
        float gap;
        PairMode mode;
    };
    std::vector<TrailingPair> m_trailing;   ///< classifyFrom's: the pairs that do not lead
    std::vector<PairMode> m_mode;           ///< per pair
    std::vector<std::uint8_t> m_hint;       ///< per pair: history slot of its spring, last time
    std::vector<KeptSpring> m_springs;      ///< per pair once one is kept: the kept springs
    std::vector<std::uint32_t> m_indexOf;   ///< per id
    using Reference = std::array<float, 3>; ///< position - m_origin, rounded to nearest
    /// Stores x's reference and widens the slack if x lies farther from the origin.
    void pushReference(core::Vec3 const& x);
    /// Widens the reference slack to the current origin and extent.
    void widenSlack();

    std::vector<Reference> m_reference; ///< per id
    core::Vec3 m_origin = core::Vec3::Zero();
    core::Vec3 m_builtOrigin = core::Vec3::Zero(); ///< m_origin at the last restart
    core::Vec3 m_common = core::Vec3::Zero();      ///< setCommonDisplacement, less the shifts since
    double m_extent = 0.0; ///< largest |coordinate - origin| of a stored reference
    double m_referenceSlack = 0.0;
    std::vector<Id> m_arrivals;
};

} // namespace regolith::particles
