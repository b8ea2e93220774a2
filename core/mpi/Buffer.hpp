#pragma once
/// Typed message buffers: `send << x` packs, `recv >> x` unpacks. Supported: trivially
/// copyable values (PODs, enums, Eigen fixed-size vectors), std::string, std::vector and
/// std::array of those, nested. Every read is bounds-checked: a short or corrupt buffer
/// throws core::BufferError naming what was being read, never reads past the end.
#include "core/Error.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

namespace regolith::core {

template <class T>
concept Packable = std::is_trivially_copyable_v<T>;

/// The bytes are written into storage that only grows (zero-filled once, when it grows), so
/// that a value of known size packs as one store: a shadow's state goes out every step.
class SendBuffer {
public:
    void writeBytes(void const* data, std::size_t n) {
        if (n > m_data.size() - m_size) [[unlikely]]
            grow(n);
        if (n > 0) // an empty vector or string: memcpy from a null pointer is undefined
            std::memcpy(m_data.data() + m_size, data, n);
        m_size += n;
    }
    [[nodiscard]] std::size_t size() const { return m_size; }
    [[nodiscard]] bool empty() const { return m_size == 0; }
    [[nodiscard]] std::byte const* data() const { return m_data.data(); }
    [[nodiscard]] std::span<std::byte const> bytes() const { return {m_data.data(), m_size}; }
    /// Empties the buffer and keeps its storage.
    void clear() { m_size = 0; }
    void reserve(std::size_t n) {
        if (n > m_data.size())
            m_data.resize(n);
    }
    /// Moves the bytes out (e.g. into an exchange); the buffer is empty afterwards.
    [[nodiscard]] std::vector<std::byte> release();

private:
    void grow(std::size_t n);

    std::vector<std::byte> m_data; ///< storage; the first m_size bytes are the message
    std::size_t m_size = 0;
};

class RecvBuffer {
public:
    RecvBuffer() = default;
    explicit RecvBuffer(std::vector<std::byte> data)
        : m_data(std::move(data))
        , m_size(m_data.size()) {}
    /// The first `size` bytes of `storage` are the message (storage kept for the next one).
    RecvBuffer(std::vector<std::byte> storage, std::size_t size)
        : m_data(std::move(storage))
        , m_size(std::min(size, m_data.size())) {}
    RecvBuffer(RecvBuffer const&) = default;
    RecvBuffer& operator=(RecvBuffer const&) = default;
    /// A moved-from buffer is empty (its length goes with the bytes).
    RecvBuffer(RecvBuffer&& o) noexcept
        : m_data(std::move(o.m_data))
        , m_size(std::exchange(o.m_size, 0))
        , m_pos(std::exchange(o.m_pos, 0)) {}
    RecvBuffer& operator=(RecvBuffer&& o) noexcept {
        m_data = std::move(o.m_data);
        m_size = std::exchange(o.m_size, 0);
        m_pos = std::exchange(o.m_pos, 0);
        return *this;
    }
    ~RecvBuffer() = default;

    /// Copies n bytes out; throws BufferError if fewer remain.
    void readBytes(void* out, std::size_t n, char const* what) {
        if (n > remaining())
            throwShort(n, what);
        if (n == 0) // an empty vector or string: memcpy with a null pointer is undefined
            return;
        std::memcpy(out, m_data.data() + m_pos, n);
        m_pos += n;
    }
    /// Length prefix of a container: must be consistent with the bytes left, else corrupt.
    std::size_t readCount(std::size_t elementBytes, char const* what) {
        std::uint64_t n = 0;
        readBytes(&n, sizeof n, what);
        if (elementBytes > 0 && n > remaining() / elementBytes)
            throwCorrupt(n, elementBytes, what);
        return static_cast<std::size_t>(n);
    }
    [[nodiscard]] std::size_t remaining() const { return m_size - m_pos; }
    [[nodiscard]] bool exhausted() const { return remaining() == 0; }
    [[nodiscard]] std::size_t size() const { return m_size; }
    /// The storage, for the next message (the buffer is empty afterwards).
    [[nodiscard]] std::vector<std::byte> takeStorage() {
        m_size = m_pos = 0;
        return std::move(m_data);
    }

private:
    [[noreturn]] void throwShort(std::size_t n, char const* what) const;
    [[noreturn]] void throwCorrupt(std::uint64_t n, std::size_t bytes, char const* what) const;

    std::vector<std::byte> m_data;
    std::size_t m_size = 0;
    std::size_t m_pos = 0;
};

// ---- packing -----------------------------------------------------------------------------

template <Packable T>
SendBuffer& operator<<(SendBuffer& b, T const& v) {
    b.writeBytes(&v, sizeof(T));
    return b;
}
inline SendBuffer& operator<<(SendBuffer& b, std::string const& s) {
    std::uint64_t const n = s.size();
    b.writeBytes(&n, sizeof n);
    b.writeBytes(s.data(), s.size());
    return b;
}
/// A span goes as a std::vector (count, elements): it is received into one.
template <class T>
SendBuffer& operator<<(SendBuffer& b, std::span<T const> v) {
    std::uint64_t const n = v.size();
    b.writeBytes(&n, sizeof n);
    if constexpr (Packable<T>) {
        b.writeBytes(v.data(), v.size() * sizeof(T));
    } else {
        for (auto const& x : v)
            b << x;
    }
    return b;
}
template <class T>
SendBuffer& operator<<(SendBuffer& b, std::vector<T> const& v) {
    return b << std::span<T const>(v);
}
/// Fixed-size Eigen matrices and quaternions (not trivially copyable, but plain storage).
template <class S, int R, int C, int O>
SendBuffer& operator<<(SendBuffer& b, Eigen::Matrix<S, R, C, O, R, C> const& m) {
    static_assert(R > 0 && C > 0, "only fixed-size Eigen matrices are packable");
    b.writeBytes(m.data(), sizeof(S) * R * C);
    return b;
}
template <class S>
SendBuffer& operator<<(SendBuffer& b, Eigen::Quaternion<S> const& q) {
    b.writeBytes(q.coeffs().data(), sizeof(S) * 4);
    return b;
}
template <class T, std::size_t N>
requires(!Packable<std::array<T, N>>) SendBuffer& operator<<(SendBuffer& b,
                                                             std::array<T, N> const& a) {
    for (auto const& x : a)
        b << x;
    return b;
}

// ---- unpacking ---------------------------------------------------------------------------

template <Packable T>
RecvBuffer& operator>>(RecvBuffer& b, T& v) {
    b.readBytes(&v, sizeof(T), typeid(T).name());
    return b;
}
inline RecvBuffer& operator>>(RecvBuffer& b, std::string& s) {
    std::size_t const n = b.readCount(1, "std::string");
    s.resize(n);
    b.readBytes(s.data(), n, "std::string");
    return b;
}
template <class T>
RecvBuffer& operator>>(RecvBuffer& b, std::vector<T>& v) {
    if constexpr (Packable<T>) {
        std::size_t const n = b.readCount(sizeof(T), "std::vector");
        v.resize(n);
        b.readBytes(v.data(), n * sizeof(T), "std::vector");
    } else {
        // Every element takes at least one byte, which bounds a corrupt count.
        std::size_t const n = b.readCount(1, "std::vector");
        v.clear();
        v.reserve(n);
        for (std::size_t i = 0; i < n; ++i)
            b >> v.emplace_back();
    }
    return b;
}
template <class S, int R, int C, int O>
RecvBuffer& operator>>(RecvBuffer& b, Eigen::Matrix<S, R, C, O, R, C>& m) {
    static_assert(R > 0 && C > 0, "only fixed-size Eigen matrices are packable");
    b.readBytes(m.data(), sizeof(S) * R * C, "Eigen::Matrix");
    return b;
}
template <class S>
RecvBuffer& operator>>(RecvBuffer& b, Eigen::Quaternion<S>& q) {
    b.readBytes(q.coeffs().data(), sizeof(S) * 4, "Eigen::Quaternion");
    return b;
}
template <class T, std::size_t N>
requires(!Packable<std::array<T, N>>) RecvBuffer& operator>>(RecvBuffer& b, std::array<T, N>& a) {
    for (auto& x : a)
        b >> x;
    return b;
}

/// Reads a value of type T (convenience for `T x; b >> x;`).
template <class T>
T read(RecvBuffer& b) {
    T v{};
    b >> v;
    return v;
}

} // namespace regolith::core
