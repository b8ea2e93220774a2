#pragma once
/// Deterministic random traffic for the exchange tests: every rank computes the same pattern
/// from a seed, so each knows what it must receive. Payload bytes are a function of
/// (source, destination, round), so a message delivered to the wrong place, in the wrong
/// round or corrupted is detected.
#include "core/mpi/Buffer.hpp"

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace regolith::testing {

/// splitmix64 finaliser (Steele, Lea & Flood, OOPSLA 2014): a cheap 64-bit mixing function.
inline std::uint64_t mix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

inline std::uint64_t hashOf(std::initializer_list<std::uint64_t> values) {
    std::uint64_t h = 0x5EED;
    for (auto const v : values)
        h = mix64(h ^ v);
    return h;
}

inline constexpr std::size_t kMaxMessage = std::size_t{1} << 20; // 1 MiB

/// Traffic among `ranks` ranks over numbered rounds.
struct ExchangePattern {
    int ranks = 1;
    std::uint64_t seed = 1;

    static std::uint64_t u(int x) { return static_cast<std::uint64_t>(x); }

    /// Symmetric neighbour relation (self-links included) for NeighbourExchange.
    [[nodiscard]] bool linked(int a, int b) const {
        int const lo = a < b ? a : b;
        int const hi = a < b ? b : a;
        return hashOf({seed, 1, u(lo), u(hi)}) % 3 != 0;
    }
    /// Sorted peers of `rank` under linked().
    [[nodiscard]] std::vector<int> peersOf(int rank) const {
        std::vector<int> out;
        for (int q = 0; q < ranks; ++q)
            if (linked(rank, q))
                out.push_back(q);
        return out;
    }
    /// Directed, round-dependent relation for SparseExchange. Round 3 is silent everywhere,
    /// which checks that NBX terminates when nobody sends.
    [[nodiscard]] bool sends(int src, int dst, int round) const {
        if (round == 3)
            return false;
        return hashOf({seed, 2, u(src), u(dst), u(round)}) % 5 < 2;
    }
    /// Message size in bytes: every fifth (src, dst, round) is empty, every fifth 1 MiB (each
    /// pair meets both within five rounds), the rest log-uniform in [1, 2^20].
    [[nodiscard]] std::size_t size(int src, int dst, int round) const {
        int const phase = (src + 2 * dst + round) % 5;
        if (phase == 0)
            return 0;
        if (phase == 1)
            return kMaxMessage;
        std::uint64_t const h = hashOf({seed, 3, u(src), u(dst), u(round)});
        std::uint64_t const bits = h % 21; // 2^0 .. 2^20
        return static_cast<std::size_t>(1 + (h >> 8) % (std::uint64_t{1} << bits));
    }
    /// The payload of message (src, dst, round).
    [[nodiscard]] std::vector<std::byte> payload(int src, int dst, int round) const {
        std::size_t const n = size(src, dst, round);
        std::vector<std::byte> out(n);
        std::uint64_t const base = hashOf({seed, 4, u(src), u(dst), u(round)});
        for (std::size_t i = 0; i < n; i += 8) {
            std::uint64_t const w = mix64(base + i);
            for (std::size_t k = 0; k < 8 && i + k < n; ++k)
                out[i + k] = static_cast<std::byte>(w >> (8 * k));
        }
        return out;
    }
    /// Packs the payload into `b`.
    void pack(core::SendBuffer& b, int src, int dst, int round) const {
        auto const p = payload(src, dst, round);
        b.writeBytes(p.data(), p.size());
    }
    /// "" if `b` holds exactly the payload of (src, dst, round), else what differs.
    [[nodiscard]] std::string verify(core::RecvBuffer& b, int src, int dst, int round) const {
        auto const expected = payload(src, dst, round);
        if (b.remaining() != expected.size())
            return "size " + std::to_string(b.remaining()) + " != expected " +
                   std::to_string(expected.size()) + " for " + label(src, dst, round);
        std::vector<std::byte> got(expected.size());
        b.readBytes(got.data(), got.size(), "payload");
        for (std::size_t i = 0; i < got.size(); ++i)
            if (got[i] != expected[i])
                return "byte " + std::to_string(i) + " differs for " + label(src, dst, round);
        return {};
    }
    static std::string label(int src, int dst, int round) {
        return std::to_string(src) + "->" + std::to_string(dst) + " round " + std::to_string(round);
    }
};

} // namespace regolith::testing
