#pragma once
/// Growth of arrays that are sized exactly once and then grow a little: a particle storage
/// reserved for the generated masters that then receives its first shadows, a neighbour
/// list's per-copy arrays that then see a few arrivals. std::vector's push_back doubles the
/// capacity of a full vector, so the first extra element would double the memory of an
/// array of millions (and, during the copy, hold three times it). Growing by a sixteenth keeps
/// the amortised O(1) append (about 16 copies per element instead of 1 when growing from
/// empty) with at most 6.25 % slack.

#include <cstddef>

namespace regolith::core {

/// The capacity to reserve before appending one element to a full array of `size`
/// elements: about 1/16 more, at least 16 more.
[[nodiscard]] constexpr std::size_t gentleCapacity(std::size_t size) {
    return size + size / 16 + 16;
}

/// Makes room for one more element in `v` (a std::vector or alike) by gentleCapacity
/// instead of doubling. Call right before push_back / emplace_back.
template <class Vector>
void reserveForAppend(Vector& v) {
    if (v.size() == v.capacity())
        v.reserve(gentleCapacity(v.size()));
}

} // namespace regolith::core
