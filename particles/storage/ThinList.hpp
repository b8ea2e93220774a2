#pragma once
/// A per-copy small vector that is nearly always empty, e.g. the shadow holders of a master
/// (ParticleStorage::shadowHolders), with std::vector's interface as far as the
/// synchronisation uses it (iteration, sorted insert, erase, assign).
///
/// Memory: every copy has one and nearly all are empty (only masters near a block face have
/// shadows), so it is one pointer (8 bytes) to a vector that exists only while the list is
/// non-empty, instead of an inline std::vector (24 bytes). Iterators are pointers; they are
/// invalidated by every change (as std::vector's by a reallocation), and an empty list has
/// begin() == end() == nullptr.
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <vector>

namespace regolith::particles {

template <class T>
class ThinList {
public:
    using value_type = T;
    using iterator = T*;
    using const_iterator = T const*;

    ThinList() = default;
    ThinList(ThinList const& o) { *this = o; }
    ThinList& operator=(ThinList const& o) {
        if (this != &o)
            m_v = o.empty() ? nullptr : std::make_unique<std::vector<T>>(*o.m_v);
        return *this;
    }
    ThinList(ThinList&&) noexcept = default;
    ThinList& operator=(ThinList&&) noexcept = default;
    ~ThinList() = default;
    ThinList& operator=(std::vector<T> const& v) {
        assign(v.begin(), v.end());
        return *this;
    }

    [[nodiscard]] std::size_t size() const { return m_v ? m_v->size() : 0; }
    [[nodiscard]] bool empty() const { return !m_v; }
    [[nodiscard]] T* begin() { return m_v ? m_v->data() : nullptr; }
    [[nodiscard]] T* end() { return m_v ? m_v->data() + m_v->size() : nullptr; }
    [[nodiscard]] T const* begin() const { return m_v ? m_v->data() : nullptr; }
    [[nodiscard]] T const* end() const { return m_v ? m_v->data() + m_v->size() : nullptr; }
    [[nodiscard]] T& operator[](std::size_t k) { return (*m_v)[k]; }
    [[nodiscard]] T const& operator[](std::size_t k) const { return (*m_v)[k]; }
    [[nodiscard]] T const& at(std::size_t k) const {
        if (k >= size())
            throw std::out_of_range("ThinList::at");
        return (*m_v)[k];
    }
    [[nodiscard]] T const& front() const { return (*m_v).front(); }
    [[nodiscard]] T const& back() const { return (*m_v).back(); }
    /// The elements as a std::vector (a shared empty one when there are none), e.g. for
    /// message buffers.
    [[nodiscard]] std::vector<T> const& vector() const { return m_v ? *m_v : kEmpty; }

    void push_back(T const& x) { ensure().push_back(x); }
    void pop_back() {
        m_v->pop_back();
        dropIfEmpty();
    }
    T* insert(T const* pos, T const& x) {
        std::ptrdiff_t const at = pos - begin();
        auto& v = ensure();
        v.insert(v.begin() + at, x);
        return v.data() + at;
    }
    T* erase(T const* first, T const* last) {
        if (first == last)
            return const_cast<T*>(first); // NOLINT(cppcoreguidelines-pro-type-const-cast)
        std::ptrdiff_t const a = first - begin(), b = last - begin();
        m_v->erase(m_v->begin() + a, m_v->begin() + b);
        dropIfEmpty();
        return begin() + (m_v ? a : 0);
    }
    template <class It>
    void assign(It first, It last) {
        if (first == last) {
            m_v.reset();
            return;
        }
        ensure().assign(first, last);
    }
    void clear() { m_v.reset(); }

    /// Heap bytes held.
    [[nodiscard]] std::size_t heapBytes() const {
        return m_v ? sizeof(*m_v) + m_v->capacity() * sizeof(T) : 0;
    }
    friend bool operator==(ThinList const& a, ThinList const& b) {
        return a.vector() == b.vector();
    }

private:
    std::vector<T>& ensure() {
        if (!m_v)
            m_v = std::make_unique<std::vector<T>>();
        return *m_v;
    }
    void dropIfEmpty() {
        if (m_v && m_v->empty())
            m_v.reset();
    }

    static inline std::vector<T> const kEmpty{}; // constant-initialised
    /// Null when empty (invariant: never points to an empty vector).
    std::unique_ptr<std::vector<T>> m_v;
};

} // namespace regolith::particles
