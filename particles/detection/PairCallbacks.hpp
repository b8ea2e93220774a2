#pragma once
/// What the fused detect (ContactDetector::detect with a pair callback) hands a callback, by
/// what the callback takes: Contact or PairOverlap, with the history slot hint or a kept
/// spring (DetectorConfig::keepSprings).
#include "particles/detection/Contact.hpp"
#include "particles/detection/VerletList.hpp"

#include <bit>
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

/// A callback that takes kept springs and, for a block of kept pairs in one image, all of its
/// overlapping pairs at once: keptHits(i, j, at, hits, springs), pair t (bit t of `hits`)
/// joining copies i[t] and j[t] with its spring at springs[at[t]].
template <class OnPair>
concept TakesKeptHits = TakesKeptSprings<OnPair> &&
    requires(OnPair& f, std::uint32_t const* ids, std::uint64_t hits, KeptSpring* springs) {
    f.keptHits(ids, ids, ids, hits, springs);
};

namespace detection_detail {
/// Hands the overlapping pairs `hits` of a block of kept pairs in one image to onPair (see
/// TakesKeptHits), all at once where it takes them so, else one by one, in the order of
/// their bits.
template <class OnPair>
void handOverKeptHits(OnPair& onPair, std::uint32_t const* i, std::uint32_t const* j,
                      std::uint32_t const* at, std::uint64_t hits, KeptSpring* springs) {
    if constexpr (TakesKeptHits<OnPair>) {
        onPair.keptHits(i, j, at, hits, springs);
    } else {
        for (; hits != 0; hits &= hits - 1) {
            auto const t = static_cast<std::size_t>(std::countr_zero(hits));
            onPair(PairOverlap{i[t], j[t], core::Vec3::Zero()}, springs[at[t]]);
        }
    }
}

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
