#pragma once
/// What the contact detector decided once for a listed pair's life (ContactDetector, "Springs
/// kept beside the list"): the per-step loop reads it instead of repeating the decision.
#include <cstdint>

namespace regolith::particles {

/// What the per-step loop does with a listed pair.
enum class PairMode : std::uint8_t {
    /// Run the full contact-point rule (the pair may change hands before the next rebuild).
    Check = 0,
    /// Stored in canonical order (uid(first) < uid(second)); whenever the two overlap, this
    /// block evaluates them (decided at listing time for the list's life).
    Owned = 1,
    /// Owned, and the pair's tangential spring lives beside the list (spring()), not in the
    /// grains' histories, until the list writes it back (ContactDetector, "Springs kept
    /// beside the list").
    Kept = 2,
    /// Kept, and overlapping for the list's whole life (it overlapped by more than the skin
    /// when listed): evaluated without testing it.
    KeptPressed = 3,
};

/// Whether a pair of mode `m` is evaluated untested (it overlaps while the list holds).
[[nodiscard]] constexpr bool isPressed(PairMode m) {
    return m == PairMode::KeptPressed;
}

/// Whether a pair of mode `m` keeps its spring beside the list.
[[nodiscard]] constexpr bool keepsSpring(PairMode m) {
    return m == PairMode::Kept || isPressed(m);
}

} // namespace regolith::particles
