#pragma once
/// What one synchronisation call does with the update list of a sync skin (UpdateList.hpp):
/// every rank must act on the same verdict, since a refresh and the leavers' Alg. 1 are
/// collective. Each rank finds its own (ParticleSync::verdictHere); the one acted on is the
/// most demanding over the ranks, i.e. the maximum, reduced alone (ParticleSync::sync) or in
/// a reduction the caller makes anyway (DemStep's step agreement, StepAgreement.hpp).

namespace regolith::particles {

/// In increasing demand (the maximum over the ranks wins).
enum class SyncVerdict : int {
    Holds,   ///< every master within the budget of its reference and inside its block
    Leavers, ///< within the budget, but some masters left their blocks (UpdateList::leavers)
    Refresh, ///< no list, invalid, a storage changed (add, remove, re-key), or a master moved
             ///< too far
    /// A refresh found an SOS-class copy (hybrid), which the list cannot carry: for the next
    /// calls (UpdateList::kIdleCalls, twice as many after each refresh that met such a copy on
    /// this rank again, up to UpdateList::kMaxIdleCalls; the longest stretch over the ranks
    /// counts), full calls without the skin's growth and no refresh, then a refresh is tried
    /// again. Without this, every call would be a full one with grown balls plus a refresh:
    /// slower than no skin (1.4x on the bidisperse scene with r = 16); each retry adds and
    /// removes the grown balls' shadows.
    Idle,
};

} // namespace regolith::particles
