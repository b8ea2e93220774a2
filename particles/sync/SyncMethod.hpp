#pragma once
/// The three shadow-synchronisation methods and their scene names.
#include <optional>
#include <string>
#include <string_view>

namespace regolith::particles {

enum class SyncMethod {
    /// Eibl & Ruede 2018, Alg. 1 (NNS): the master alone creates, updates and removes its
    /// shadows on the neighbour blocks it overlaps; one exchange. Needs every grain smaller
    /// than the blocks it may touch.
    NextNeighbour,
    /// Eibl & Ruede 2018, Alg. 2 (SOS): the master updates its known shadows; then every copy
    /// spreads shadows one block layer further (diffusively); two exchanges. Any grain size.
    ShadowOwner,
    /// Per grain: NNS for grains small enough, SOS for the others, in the same two exchanges.
    Hybrid,
};

/// "nns", "sos", "hybrid".
[[nodiscard]] std::string_view syncMethodName(SyncMethod m);
/// The method named `name`, or nullopt.
[[nodiscard]] std::optional<SyncMethod> parseSyncMethod(std::string_view name);

struct SyncConfig {
    SyncMethod method = SyncMethod::Hybrid;
    /// Sum contact forces on masters in a canonical order (by partner uid), so that results
    /// are bitwise identical for any rank count and block layout (docs/design.md, "Reproducible
    /// mode").
    bool reproducible = false;
    /// Shadow skin [length], 0: off. When > 0, NNS-class shadows are decided for the ball
    /// grown by the skin, and between two such decisions the masters only copy their state to
    /// the shadows they have, along a list fixed at the decision, instead of running Alg. 1
    /// every step; masters that leave their blocks are decided alone. All are decided again
    /// when some master moved a skin, or a storage changed. The shadows are then a superset of
    /// Alg. 1's (copies within r + 2 skin), never fewer (UpdateList.hpp). Any number of ranks
    /// (remote shadows along the owners' send lists); method "nns" or "hybrid".
    double skin = 0.0;
    /// The contact model's interaction range [length] (AnyContactModel::interactionRange,
    /// set by DemStep): every grain's copies cover its ball grown by reach / 2 (beyond the
    /// skin), so that the block owning a contact of two grains up to `reach` apart -- whose
    /// ownership point lies in the gap, within r + gap / 2 of each centre -- holds both.
    double reach = 0.0;
};

} // namespace regolith::particles
