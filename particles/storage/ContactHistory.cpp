#include "particles/storage/ContactHistory.hpp"

#include <algorithm>
#include <memory>

namespace regolith::particles {

namespace {
bool byPartner(HistoryEntry const& e, Uid uid) {
    return e.partner < uid;
}
} // namespace

ContactHistory::ContactHistory(ContactHistory const& other) {
    assign(other.entries());
}

ContactHistory& ContactHistory::operator=(ContactHistory const& other) {
    if (this != &other)
        assign(other.entries());
    return *this;
}

void ContactHistory::release() {
    if (m_block) {
        m_block->~Block();
        ::operator delete(m_block);
        m_block = nullptr;
    }
}

void ContactHistory::reallocate(std::size_t capacity, std::size_t keep) {
    void* raw = ::operator new(Block::bytes(capacity));
    auto* block =
        new (raw) Block{static_cast<std::uint32_t>(keep), static_cast<std::uint32_t>(capacity)};
    std::uninitialized_value_construct_n(reinterpret_cast<HistoryEntry*>(block + 1), capacity);
    if (m_block)
        std::copy_n(m_block->data(), keep, block->data());
    release();
    m_block = block;
}

std::size_t ContactHistory::lowerBound(Uid partner) const {
    auto const e = entries();
    return static_cast<std::size_t>(std::lower_bound(e.begin(), e.end(), partner, byPartner) -
                                    e.begin());
}

HistoryEntry& ContactHistory::insertAt(std::size_t at, HistoryEntry const& entry) {
    std::size_t const n = size();
    if (!m_block || n == m_block->capacity)
        reallocate(std::max<std::size_t>(2, 2 * n), n);
    HistoryEntry* d = m_block->data();
    std::move_backward(d + at, d + n, d + n + 1);
    d[at] = entry;
    ++m_block->size;
    return d[at];
}

HistoryEntry const* ContactHistory::find(Uid partner) const {
    std::size_t const at = lowerBound(partner);
    return at < size() && m_block->data()[at].partner == partner ? &m_block->data()[at] : nullptr;
}

HistoryEntry* ContactHistory::find(Uid partner) {
    return const_cast<HistoryEntry*>(std::as_const(*this).find(partner));
}

HistoryEntry& ContactHistory::touch(Uid partner, std::uint32_t stamp) {
    bool again = false;
    return touchAt(partner, stamp, again);
}

HistoryEntry& ContactHistory::touchAt(Uid partner, std::uint32_t stamp, bool& again) {
    std::size_t const at = lowerBound(partner);
    if (at == size() || m_block->data()[at].partner != partner)
        return insertAt(at, HistoryEntry{partner, core::Vec3::Zero(), stamp});
    HistoryEntry& e = m_block->data()[at];
    again = e.stamp == stamp;
    e.stamp = stamp;
    return e;
}

HistoryEntry& ContactHistory::touchSlow(Uid partner, std::uint32_t stamp, std::uint8_t& hint,
                                        bool& again) {
    again = false;
    HistoryEntry& e = touchAt(partner, stamp, again);
    auto const slot = static_cast<std::size_t>(&e - m_block->data());
    // Beyond 255 entries the hint saturates and always misses (then touch() searches).
    hint = static_cast<std::uint8_t>(std::min<std::size_t>(slot, 255));
    return e;
}

void ContactHistory::set(HistoryEntry const& entry) {
    std::size_t const at = lowerBound(entry.partner);
    if (at < size() && m_block->data()[at].partner == entry.partner)
        m_block->data()[at] = entry;
    else
        insertAt(at, entry);
}

void ContactHistory::assign(std::span<HistoryEntry const> entries) {
    if (entries.empty()) {
        release();
        return;
    }
    if (!m_block || m_block->capacity < entries.size())
        reallocate(entries.size(), 0);
    std::copy(entries.begin(), entries.end(), m_block->data());
    m_block->size = static_cast<std::uint32_t>(entries.size());
}

bool ContactHistory::erase(Uid partner) {
    std::size_t const at = lowerBound(partner);
    std::size_t const n = size();
    if (at == n || m_block->data()[at].partner != partner)
        return false;
    HistoryEntry* d = m_block->data();
    std::move(d + at + 1, d + n, d + at);
    if (--m_block->size == 0)
        release();
    return true;
}

std::size_t ContactHistory::keepOnlySlow(std::uint32_t stamp) {
    HistoryEntry* d = m_block->data();
    std::size_t const before = m_block->size;
    std::size_t const kept = static_cast<std::size_t>(
        std::remove_if(d, d + before, [stamp](HistoryEntry const& e) { return e.stamp != stamp; }) -
        d);
    m_block->size = static_cast<std::uint32_t>(kept);
    if (kept == 0)
        release(); // a particle that lost all contacts gives its memory back
    return before - kept;
}

} // namespace regolith::particles
