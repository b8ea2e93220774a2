#pragma once
/// Per-particle state bits (mesa_pd's `Flags`): shadow or master, fixed, global, and the
/// synchronisation class of the grain.
#include <cstdint>

namespace regolith::particles {

enum class Flag : std::uint8_t {
    /// A read-only copy of a particle owned by another block (absent: this copy is the master).
    Shadow = 1U << 0U,
    /// Never moves: infinite mass and inertia for contacts, skipped by the integrators.
    Fixed = 1U << 1U,
    /// Known on every rank (e.g. a boulder larger than the domain); not migrated.
    Global = 1U << 2U,
    /// The grain's copies spread shadows to their neighbours (SOS class, see
    /// particles/sync/ParticleSync.hpp); absent: its master alone manages its shadows (NNS).
    Spreads = 1U << 3U,
    /// (SOS class) The master's block and its neighbours hold the whole ball (the NNS
    /// condition) and the master stayed in its block at the last sync: the master itself then
    /// ordered, in round 1, a copy on every block the grain overlaps, so its shadows only test
    /// whether they still overlap theirs (particles/sync/ParticleSync.cpp, SpreadRound.cpp).
    MasterReachesAll = 1U << 4U,
};

/// A set of `Flag`s in one byte.
class Flags {
public:
    constexpr Flags() = default;
    constexpr Flags(Flag f) // NOLINT(google-explicit-constructor): a flag is a one-flag set
        : m_bits(static_cast<std::uint8_t>(f)) {}
    /// The set whose byte is `bits` (as bits() gave it, e.g. read back from a checkpoint).
    [[nodiscard]] static constexpr Flags fromBits(std::uint8_t bits) {
        Flags f;
        f.m_bits = bits;
        return f;
    }

    [[nodiscard]] constexpr bool has(Flag f) const {
        return (m_bits & static_cast<std::uint8_t>(f)) != 0;
    }
    constexpr Flags& set(Flag f, bool on = true) {
        auto const b = static_cast<std::uint8_t>(f);
        m_bits = static_cast<std::uint8_t>(on ? (m_bits | b) : (m_bits & ~b));
        return *this;
    }
    [[nodiscard]] constexpr bool isMaster() const { return !has(Flag::Shadow); }
    [[nodiscard]] constexpr bool isShadow() const { return has(Flag::Shadow); }
    [[nodiscard]] constexpr bool isFixed() const { return has(Flag::Fixed); }
    [[nodiscard]] constexpr bool isGlobal() const { return has(Flag::Global); }
    [[nodiscard]] constexpr std::uint8_t bits() const { return m_bits; }

    friend constexpr Flags operator|(Flags a, Flags b) {
        Flags r;
        r.m_bits = static_cast<std::uint8_t>(a.m_bits | b.m_bits);
        return r;
    }
    friend constexpr bool operator==(Flags, Flags) = default;

private:
    std::uint8_t m_bits = 0;
};

constexpr Flags operator|(Flag a, Flag b) {
    return Flags(a) | Flags(b);
}

} // namespace regolith::particles
