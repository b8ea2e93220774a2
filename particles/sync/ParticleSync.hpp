#pragma once
/// Shadow synchronisation between the blocks of a forest: next-neighbour (NNS, Eibl & Ruede
/// 2018 Alg. 1), shadow-owner (SOS, Alg. 2) and a per-grain hybrid of both, plus the
/// reduction of shadow forces, torques and contact history to the masters.
#include "core/mpi/Comm.hpp"
#include "core/mpi/CommCounters.hpp"
#include "core/mpi/NeighbourExchange.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "particles/kernels/ForceRecord.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/SyncMethod.hpp"
#include "particles/sync/SyncVerdict.hpp"

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace regolith::particles {

class UpdateList;

/// What one call did on this rank (for tests, counters and the run summary).
struct SyncStats {
    std::uint64_t created = 0;     ///< shadows created here
    std::uint64_t updated = 0;     ///< shadows updated here
    std::uint64_t removed = 0;     ///< shadows removed here
    std::uint64_t transferred = 0; ///< masters that moved to another block (received here)
    std::uint64_t leftDomain = 0;  ///< masters removed from this rank: they left an open domain
    /// Those masters, each with its position outside the domain (the caller tells a grain that
    /// passed through a wall from one that left through an open face).
    std::vector<std::pair<Uid, core::Vec3>> departed;
    std::uint64_t duplicates = 0; ///< creation orders discarded as duplicates (SOS)
    core::CommStats comm;         ///< messages, bytes and peers of this call's exchanges
    /// The call only copied masters to their shadows along the list of the last refresh
    /// (SyncConfig::skin, UpdateList.hpp): no decision, no message.
    bool alongList = false;
    /// The call ran Alg. 1 only for the masters that left their blocks, and copied along the
    /// list for the others (SyncConfig::skin).
    bool leaversOnly = false;
    /// And the list then followed the slots that call wrote (UpdateList::followLeavers)
    /// instead of deciding every copy again.
    bool listFollowed = false;
    /// A full call without the skin's growth: some rank held an SOS-class copy at the last
    /// refresh, which no list can carry (SyncVerdict::Idle).
    bool skinIdle = false;
};

/// A grain too large for NNS, found by `findNnsViolation`.
struct NnsViolation {
    Uid uid = kInvalidUid;
    double radius = 0.0;
    double blockEdge = 0.0; ///< the smallest edge of the blocks the grain may touch
    /// Over every violating master of this rank: whether one is too large even without the
    /// skin, and the smallest edge - radius (below it a skin would let all of them through).
    bool radiusAlone = false;
    double skinBound = std::numeric_limits<double>::infinity();
};

/// One object per run (it keeps the exchanges and counters). Every member function that
/// communicates is COLLECTIVE over the communicator given to the constructor.
class ParticleSync {
public:
    /// COLLECTIVE over `comm` (duplicates it for its exchanges).
    ParticleSync(core::Comm const& comm, domain::BlockForest const& forest, SyncConfig config);
    ~ParticleSync();
    ParticleSync(ParticleSync const&) = delete;
    ParticleSync& operator=(ParticleSync const&) = delete;

    /// For a new assignment of the blocks (a rebalance): the exchanges and the update list
    /// start anew on `forest`, whose LocalParticles hold masters only; the configuration and
    /// the counters go on. The next call must be syncUntilConverged (DemStep::relocated).
    /// COLLECTIVE.
    void relocate(domain::BlockForest const& forest);

    /// One synchronisation call with the configured method. Post (NNS-class grains): every
    /// block the grain overlaps holds exactly one copy per overlapping image, no other block
    /// holds one, masters sit in the block containing their centre. With a skin
    /// (SyncConfig::skin): every block the grain overlaps holds one, others may hold one within
    /// r + 2 skin, and most calls only copy along the list of the last refresh (UpdateList).
    /// SOS-class grains spread one block layer further per call; once converged one call per step
    /// keeps all consistent. Throws core::Error (one rank; the app aborts) if NNS meets a grain too
    /// large for it or a message is malformed. COLLECTIVE.
    ///
    /// `movedAtMost`: a bound on every master's displacement since the previous call (the
    /// integrator's, DemStep::step), +inf if unknown. With a skin it spares the check of every
    /// master against its reference (UpdateList::check); it must hold, or copies go missing.
    void sync(LocalParticles& local, double movedAtMost = std::numeric_limits<double>::infinity());
    /// sync() in two parts, for a caller that reduces the verdict with values of its own
    /// (DemStep, StepAgreement.hpp): verdictHere() is this rank's (SyncVerdict.hpp; local,
    /// Refresh without a sync skin), syncOn() acts on `agreed`, the maximum of every rank's.
    /// sync(local, movedAtMost) is syncOn(local, that maximum). syncOn is COLLECTIVE.
    [[nodiscard]] SyncVerdict verdictHere(LocalParticles const& local, double movedAtMost);
    void syncOn(LocalParticles& local, SyncVerdict agreed);

    /// Calls sync() until no shadow was created anywhere (at most `maxCalls` calls; one
    /// all-reduce per call). For set-up: a large grain spanning k block layers needs k calls.
    /// Returns the number of calls made. COLLECTIVE.
    int syncUntilConverged(LocalParticles& local, int maxCalls = 1000);

    /// Sends the forces and torques accumulated on shadows to their masters and adds them
    /// there, together with the contact-history entries stamped `stamp` (a shadow may evaluate
    /// a contact whose spring lives on its master); then, every kHistoryPruneInterval passes,
    /// drops on masters every history entry not stamped `stamp`. Shadows' forces are zeroed.
    /// COLLECTIVE.
    void reduceForces(LocalParticles& local, std::uint32_t stamp);
    /// The same, the caller knowing whether listHoldsHere() on every rank (`listEverywhere`,
    /// from a reduction it makes anyway: DemStep): one all-reduce fewer. The shares go along
    /// the update list if so, by key otherwise. COLLECTIVE.
    void reduceForces(LocalParticles& local, std::uint32_t stamp, bool listEverywhere);
    /// Whether the update list of a sync skin holds here for reduceForces: valid, and no
    /// storage changed since its last refresh (false without one). Local.
    [[nodiscard]] bool listHoldsHere(LocalParticles const& local) const;

    /// Passes between two prunes of the masters' contact histories. An entry left over from a
    /// broken contact is harmless meanwhile: ContactHistory::touch restarts an entry that the
    /// previous pass did not touch from a zero spring, as a new one. Visiting every history
    /// each pass cost 4 % of a static packing's step.
    static constexpr std::uint32_t kHistoryPruneInterval = 16;

    /// Reproducible variant: `records[b]` holds the per-contact force records of local block
    /// b (ContactEvaluation's evaluateContactsRecorded); records of shadows travel to the
    /// master, and every master's force and torque are summed from zero in ascending partner
    /// uid, so the result does not depend on which block evaluated which contact. COLLECTIVE.
    void reduceForces(LocalParticles& local, std::vector<std::vector<ForceRecord>>& records,
                      std::uint32_t stamp);

    /// The first grain on this rank (lowest uid) too large for NNS in its block, if any:
    /// radius + sync skin >= the smallest edge of its block and of the neighbour blocks it
    /// overlaps, with what all such grains of this rank share (NnsViolation). Local.
    /// (NnsApplicability.cpp, as requireNnsApplicable.)
    [[nodiscard]] std::optional<NnsViolation> findNnsViolation(LocalParticles const& local) const;
    /// Throws core::InputError on every rank, naming the uid, its radius, the block edge and
    /// the remedy, if the configured method is NNS and any rank holds such a grain. COLLECTIVE.
    void requireNnsApplicable(LocalParticles const& local) const;

    /// Makes the copies cover an interaction range of `range` beyond the radii
    /// (SyncConfig::reach), if they do not yet; the next call decides every shadow anew.
    /// Before a sync call, on every rank alike (DemStep's constructor). Not collective.
    void coverReach(double range);

    [[nodiscard]] SyncConfig const& config() const { return m_config; }
    [[nodiscard]] SyncStats const& lastStats() const { return m_last; }
    /// Whether the last reduceForces(local, stamp) went along the skin's list (the same on
    /// every rank), not by key.
    [[nodiscard]] bool lastReductionAlongList() const { return m_reducedAlongList; }
    /// Totals over all calls of sync() and reduceForces() since construction or reset.
    [[nodiscard]] core::CommCounters const& counters() const { return m_counters; }
    void resetCounters() { m_counters.reset(); }

    /// Relative safety margin of the overlap test that decides where copies are needed: a
    /// copy exists where dist(centre, box) < r (1 + kOverlapMargin), so that rounding can never
    /// hide a copy from the block that must evaluate a contact.
    static constexpr double kOverlapMargin = 1e-9;

    /// Internals (SyncEngine.hpp), shared by the implementation files only.
    class Impl;

private:
    /// The synchronisation without the update list (Alg. 1 / 2): for the masters the scan
    /// picks, or, if `only` is not empty, for the masters only[b] of each local block b; the
    /// NNS-class balls grown by `grow` (the skin, or 0).
    void syncInFull(LocalParticles& local, std::span<std::vector<std::uint32_t> const> only,
                    double grow);
    /// After a call along a valid list (refresh or leavers): the shadows in their master's
    /// storage share its history again, or, if the list no longer holds, get a copy of it.
    void shareHistoriesAgain(LocalParticles& local);

    core::Comm const* m_comm;
    std::unique_ptr<Impl> m_impl;
    std::unique_ptr<UpdateList> m_updateList; ///< with a skin only
    SyncConfig m_config;
    SyncStats m_last;
    bool m_reducedAlongList = false;
    core::CommCounters m_counters;
};

/// The overlap predicate of the synchronisation (see kOverlapMargin): does the ball at
/// canonical position `x`, image `k`, radius `r` reach into `box`? Invariant checks use it.
[[nodiscard]] inline bool copyNeeded(core::AABB const& box, core::Vec3 const& x, CopyImage const& k,
                                     double r, core::Vec3 const& period) {
    return box.intersectsSphere(localPosition(x, k, period),
                                r * (1.0 + ParticleSync::kOverlapMargin));
}

} // namespace regolith::particles
