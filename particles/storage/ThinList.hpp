#pragma once
/// A per-copy small vector that is nearly always empty, e.g. the shadow holders of a master
/// (ParticleStorage::shadowHolders), with std::vector's interface as far as the
/// synchronisation uses it (iteration, sorted insert, erase, assign).
///
/// Memory: every copy has one and nearly all are empty (only masters near a block face have
/// shadows), so it is one pointer (8 bytes), null while empty, to ONE heap block holding the
/// count, the capacity and the elements — not a pointer to a std::vector, whose buffer is a
/// second dependent load: the synchronisation reads the holders of every master near a face
/// every step, at scattered addresses (as ContactHistory). Iterators are
/// pointers; they are invalidated by every change, and an empty list has begin() == end() ==
/// nullptr. T must be trivially destructible (freeing a block is just deallocation).
/// ContactHistory keeps its entries in one.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

namespace regolith::particles {

template <class T>
class ThinList {
    static_assert(std::is_trivially_destructible_v<T>);

public:
    using value_type = T;
    using iterator = T*;
    using const_iterator = T const*;

    ThinList() = default;
    ThinList(ThinList const& o) { assign(o.begin(), o.end()); }
    ThinList& operator=(ThinList const& o) {
        if (this != &o)
            assign(o.begin(), o.end());
        return *this;
    }
    ThinList(ThinList&& o) noexcept
        : m_block(std::exchange(o.m_block, nullptr)) {}
    ThinList& operator=(ThinList&& o) noexcept {
        if (this != &o) {
            clear();
            m_block = std::exchange(o.m_block, nullptr);
        }
        return *this;
    }
    ~ThinList() { clear(); }
    ThinList& operator=(std::vector<T> const& v) {
        assign(v.begin(), v.end());
        return *this;
    }

    [[nodiscard]] std::size_t size() const { return m_block ? m_block->size : 0; }
    [[nodiscard]] bool empty() const { return !m_block; }
    [[nodiscard]] T* begin() { return m_block ? m_block->data() : nullptr; }
    [[nodiscard]] T* end() { return m_block ? m_block->data() + m_block->size : nullptr; }
    [[nodiscard]] T const* begin() const { return m_block ? m_block->data() : nullptr; }
    [[nodiscard]] T const* end() const {
        return m_block ? m_block->data() + m_block->size : nullptr;
    }
    [[nodiscard]] T& operator[](std::size_t k) { return m_block->data()[k]; }
    [[nodiscard]] T const& operator[](std::size_t k) const { return m_block->data()[k]; }
    [[nodiscard]] T const& at(std::size_t k) const {
        if (k >= size())
            throw std::out_of_range("ThinList::at");
        return (*this)[k];
    }
    [[nodiscard]] T const& front() const { return (*this)[0]; }
    [[nodiscard]] T const& back() const { return (*this)[size() - 1]; }
    /// The elements as a std::vector (a copy), e.g. for message buffers.
    [[nodiscard]] std::vector<T> vector() const { return std::vector<T>(begin(), end()); }
    /// Starts loading the block into the cache (the synchronisation calls it a few masters
    /// ahead of reading the holders).
    [[gnu::always_inline]] void prefetch() const { __builtin_prefetch(m_block); }

    void push_back(T const& x) { (void)insert(end(), x); }
    void pop_back() {
        if (--m_block->size == 0)
            clear();
    }
    T* insert(T const* pos, T const& x) {
        std::size_t const at = static_cast<std::size_t>(pos - begin());
        std::size_t const n = size();
        if (n == capacity())
            reallocate(std::max<std::size_t>(2, 2 * n), n);
        T* d = m_block->data();
        std::move_backward(d + at, d + n, d + n + 1);
        d[at] = x;
        m_block->size = static_cast<std::uint32_t>(n + 1);
        return d + at;
    }
    T* erase(T const* first, T const* last) {
        if (first == last)
            return const_cast<T*>(first); // NOLINT(cppcoreguidelines-pro-type-const-cast)
        std::size_t const a = static_cast<std::size_t>(first - begin());
        std::size_t const b = static_cast<std::size_t>(last - begin());
        std::size_t const n = size();
        T* d = m_block->data();
        std::move(d + b, d + n, d + a);
        m_block->size = static_cast<std::uint32_t>(n - (b - a));
        if (m_block->size == 0) {
            clear();
            return nullptr;
        }
        return d + a;
    }
    template <class It>
    void assign(It first, It last) {
        auto const n = static_cast<std::size_t>(std::distance(first, last));
        if (n == 0) {
            clear();
            return;
        }
        if (n > capacity())
            reallocate(n, 0);
        std::copy(first, last, m_block->data());
        m_block->size = static_cast<std::uint32_t>(n);
    }
    void clear() {
        ::operator delete(m_block);
        m_block = nullptr;
    }

    /// Heap bytes held (capacity, not size).
    [[nodiscard]] std::size_t heapBytes() const {
        return m_block ? Block::bytes(m_block->capacity) : 0;
    }
    friend bool operator==(ThinList const& a, ThinList const& b) {
        return std::equal(a.begin(), a.end(), b.begin(), b.end());
    }

private:
    /// The heap block: this header, then `capacity` elements (all constructed; the first
    /// `size` in use).
    struct Block {
        std::uint32_t size;
        std::uint32_t capacity;
        static std::size_t bytes(std::size_t capacity) {
            return sizeof(Block) + capacity * sizeof(T);
        }
        T* data() { return std::launder(reinterpret_cast<T*>(this + 1)); }
        T const* data() const { return std::launder(reinterpret_cast<T const*>(this + 1)); }
    };
    static_assert(sizeof(Block) % alignof(T) == 0 && alignof(T) <= alignof(std::max_align_t));

    [[nodiscard]] std::size_t capacity() const { return m_block ? m_block->capacity : 0; }
    /// A block of `capacity` elements holding the first `keep` of the current one.
    void reallocate(std::size_t capacity, std::size_t keep) {
        auto* block = ::new (::operator new(Block::bytes(capacity)))
            Block{static_cast<std::uint32_t>(keep), static_cast<std::uint32_t>(capacity)};
        std::uninitialized_value_construct_n(block->data(), capacity);
        if (keep > 0)
            std::copy_n(m_block->data(), keep, block->data());
        ::operator delete(m_block);
        m_block = block;
    }

    /// Null when empty (invariant: never points to a block with no elements).
    Block* m_block = nullptr;
};

} // namespace regolith::particles
