#include "particles/sync/SentCache.hpp"

#include <algorithm>
#include <tuple>

namespace regolith::particles {

namespace {

bool before(SentEntry const& a, SentEntry const& b) {
    return std::tie(a.uid, a.block, a.image) < std::tie(b.uid, b.block, b.image);
}

/// The contiguous range of `uid`'s entries.
template <class It>
std::pair<It, It> rangeOf(It first, It last, Uid uid) {
    auto const lo =
        std::lower_bound(first, last, uid, [](SentEntry const& e, Uid u) { return e.uid < u; });
    auto const hi =
        std::upper_bound(lo, last, uid, [](Uid u, SentEntry const& e) { return u < e.uid; });
    return {lo, hi};
}

} // namespace

bool SentCache::insert(SentEntry const& e) {
    auto const at = std::lower_bound(m_entries.begin(), m_entries.end(), e, before);
    if (at != m_entries.end() && *at == e)
        return false;
    m_entries.insert(at, e);
    return true;
}

bool SentCache::contains(SentEntry const& e) const {
    auto const at = std::lower_bound(m_entries.begin(), m_entries.end(), e, before);
    return at != m_entries.end() && *at == e;
}

bool SentCache::erase(SentEntry const& e) {
    auto const at = std::lower_bound(m_entries.begin(), m_entries.end(), e, before);
    if (at == m_entries.end() || !(*at == e))
        return false;
    m_entries.erase(at);
    return true;
}

void SentCache::forget(Uid uid) {
    if (m_entries.empty())
        return;
    auto const [lo, hi] = rangeOf(m_entries.begin(), m_entries.end(), uid);
    m_entries.erase(lo, hi);
}

void SentCache::shift(Uid uid, CopyImage const& delta) {
    auto const [lo, hi] = rangeOf(m_entries.begin(), m_entries.end(), uid);
    if (lo == hi)
        return;
    for (auto it = lo; it != hi; ++it)
        it->image = subtractImages(it->image, delta);
    // The range keeps its uid, so re-sorting it in place restores the order; shifting every
    // image by the same delta is injective, so no duplicates appear.
    std::sort(lo, hi, before);
}

} // namespace regolith::particles
