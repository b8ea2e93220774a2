#pragma once
/// What the fused detect (ContactDetector::detect with a pair callback) hands a callback, by
/// what the callback takes: Contact or PairOverlap, with the history slot hint or a kept
/// spring (DetectorConfig::keepSprings).
#include "particles/detection/Contact.hpp"
#include "particles/detection/VerletList.hpp"

#include <concepts>
#include <cstddef>
#include <cstdint>

namespace regolith::particles {

/// A pair callback of the fused detect that takes PairOverlap (and computes the geometry
/// itself) rather than Contact.
template <class OnPair>
concept TakesPairOverlaps = std::invocable<OnPair&, PairOverlap const&, std::uint8_t&>;
/// A pair callback that also takes a kept pair's spring (KeptSpring&, beside the list:
/// DetectorConfig::keepSprings) in place of the history hint, and tells the pass
/// (ContactHistory stamp) it evaluates, `pass()`.
template <class OnPair>
concept TakesKeptSprings = requires(OnPair& f) {
    { f.pass() } -> std::convertible_to<std::uint32_t>; // the stamp it evaluates with
}
&&(std::invocable<OnPair&, PairOverlap const&, KeptSpring&> ||
   std::invocable<OnPair&, Contact const&, KeptSpring&>);

namespace detection_detail {
/// Hands contact `c` to onPair in the form it takes: with its kept spring if it has one
/// (non-null) and onPair takes it, else with its history hint.
template <class OnPair>
void handOver(OnPair& onPair, Contact const& c, std::uint8_t& hint, KeptSpring* kept = nullptr) {
    if constexpr (TakesKeptSprings<OnPair>) {
        if (kept != nullptr) {
            if constexpr (TakesPairOverlaps<OnPair>)
                onPair(PairOverlap::of(c), *kept);
            else
                onPair(c, *kept);
            return;
        }
    }
    if constexpr (TakesPairOverlaps<OnPair>)
        onPair(PairOverlap::of(c), hint);
    else
        onPair(c, hint);
}
} // namespace detection_detail

} // namespace regolith::particles
