#pragma once
/// What the ranks agree on in a DEM step (DemStep::step), and why. Each of these decisions must
/// come out the same on every rank (a rank that refreshes, rebuilds or reduces alone waits for
/// messages that never come, or diverges), and every all-reduce is a point where the ranks wait
/// for each other: so they are reduced together, as a few doubles under one element-wise
/// maximum, once before the synchronisation and, only in the steps that need it, once after.
/// LAMMPS agrees once per step (its neighbour check, Neighbor::decide).
#include "core/mpi/Comm.hpp"
#include "particles/sync/SyncVerdict.hpp"

#include <array>
#include <limits>

namespace regolith::particles {

/// Every step, before the synchronisation.
struct BeforeSyncAgreement {
    /// The largest distance a copy moved since the last synchronisation (the integrator's
    /// bound): the bound the sync skin's list and the Verlet lists go by, since a block's
    /// shadows may have their masters on another rank.
    double moved = 0.0;
    /// The largest share of a block's reach a master moved in one step, and the smallest edge
    /// among the blocks with that share: a grain beyond the neighbour blocks the
    /// synchronisation reaches is refused on every rank, naming the edge.
    double share = 0.0;
    double edge = std::numeric_limits<double>::infinity();
    /// The sync skin's list: along it, for the leavers only, or a refresh (collective).
    SyncVerdict verdict = SyncVerdict::Holds;
    /// The largest motion under which no rank's Verlet list can come due
    /// (ContactDetector::quietMotion; the smallest over the ranks).
    double quiet = std::numeric_limits<double>::infinity();

    /// Whether a Verlet list may come due in this step, on some rank: a storage changed in
    /// the synchronisation (a verdict other than Holds), or the motion exceeds `quiet`.
    [[nodiscard]] bool listsMayComeDue() const {
        return verdict != SyncVerdict::Holds || !(moved <= quiet);
    }
    /// The agreement of every rank, in place: one all-reduce, none on one rank. COLLECTIVE.
    void reduce(core::Comm const& comm);
};

/// After the synchronisation, before the contacts: only in a step where a Verlet list may come
/// due (BeforeSyncAgreement::listsMayComeDue) or a body force votes. Otherwise no list is due,
/// the body forces have no vote, and the sync skin's list holds on every rank (the verdict
/// Holds on every rank, and nothing changed a storage since).
struct AfterSyncAgreement {
    /// Some Verlet list is due: every list that has used half its skin rebuilds in this step
    /// too, so that the ranks rebuild together (DemStep::agreeAfterSync).
    bool listDue = false;
    /// The body forces' vote (DemStep::BodyForceVote).
    std::array<double, 2> bodyForceVote{};
    /// The sync skin's list holds on every rank: the forces go back along it, else by key.
    bool syncListHolds = true;

    /// The agreement of every rank, in place: one all-reduce, none on one rank. COLLECTIVE.
    void reduce(core::Comm const& comm);
};

} // namespace regolith::particles
