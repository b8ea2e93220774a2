#pragma once
/// Identity of a block in the forest: which root block it descends from and the octree path
/// from that root down to it, packed into one 64-bit word.
#include <compare>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>

namespace regolith::domain {

/// Value type wrapping a uint64 laid out as
///
///     [ root index : 64 - kPathBits ][ 0...0 | 1 (marker) | d1 d2 ... dL (3 bits each) ]
///
/// The low kPathBits hold the path: a marker bit followed by one octant digit per level, so the
/// level is recoverable from the marker position (the layout of waLBerla's BlockID, with the
/// root index moved to fixed high bits so that it can be read without knowing the level).
/// Octant digit k of a child: bit 0 = upper half in x, bit 1 = in y, bit 2 = in z (Morton order).
/// A default-constructed id is invalid (no marker bit).
class BlockId {
public:
    /// Deepest level an id can encode (the forest itself allows less, see SpecValidation.hpp).
    static constexpr int kMaxLevel = 12;
    static constexpr int kPathBits = 1 + 3 * kMaxLevel;
    /// Largest root index that fits in the high bits (2^27 - 1).
    static constexpr std::uint64_t kMaxRootIndex = (std::uint64_t{1} << (64 - kPathBits)) - 1;

    constexpr BlockId() = default;

    /// The root block `rootIndex` (level 0). Throws core::Error if rootIndex > kMaxRootIndex.
    [[nodiscard]] static BlockId root(std::uint64_t rootIndex);
    /// Reinterprets a raw word (e.g. received in a message); use isValid() to check it.
    [[nodiscard]] static constexpr BlockId fromRaw(std::uint64_t raw) {
        BlockId id;
        id.m_raw = raw;
        return id;
    }

    [[nodiscard]] constexpr std::uint64_t raw() const { return m_raw; }
    /// True if the marker bit is present and no level exceeds kMaxLevel.
    [[nodiscard]] bool isValid() const;
    /// Refinement level: 0 for a root block. Pre: isValid().
    [[nodiscard]] int level() const;
    [[nodiscard]] constexpr std::uint64_t rootIndex() const { return m_raw >> kPathBits; }
    /// Octant digit (0..7) taken at level `l` in [1, level()] on the way down from the root.
    [[nodiscard]] int octantAt(int l) const;
    /// The last octant digit, i.e. where this block sits in its parent. Pre: level() > 0.
    [[nodiscard]] int octant() const { return octantAt(level()); }
    /// The enclosing block one level up. Throws core::Error on a root.
    [[nodiscard]] BlockId parent() const;
    /// Child in octant k (0..7). Throws core::Error if k is out of range or level() == kMaxLevel.
    [[nodiscard]] BlockId child(int k) const;
    /// True if `other` is this block or lies inside it (same root, path prefix).
    [[nodiscard]] bool isAncestorOf(BlockId other) const;

    /// "root" for a root block, "root.d1.d2..." below it, e.g. "12.0.7".
    [[nodiscard]] std::string toString() const;

    /// Depth-first (pre-order) tree order: by root index, then an ancestor before its
    /// descendants and siblings in octant order. Sorting the leaves of one root therefore gives
    /// their Morton order. (Not the Hilbert order of the roots: that lives in ForestBuilder.)
    friend std::strong_ordering operator<=>(BlockId a, BlockId b);
    friend constexpr bool operator==(BlockId a, BlockId b) { return a.m_raw == b.m_raw; }

private:
    [[nodiscard]] std::uint64_t pathWord() const {
        return m_raw & ((std::uint64_t{1} << kPathBits) - 1);
    }

    std::uint64_t m_raw = 0;
};

std::ostream& operator<<(std::ostream& os, BlockId id);

} // namespace regolith::domain

template <>
struct std::hash<regolith::domain::BlockId> {
    /// splitmix64 finaliser (Steele, Lea, Flood 2014): ids that differ in a few low bits
    /// spread over all buckets.
    std::size_t operator()(regolith::domain::BlockId id) const noexcept {
        std::uint64_t z = id.raw() + 0x9e3779b97f4a7c15ULL;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return static_cast<std::size_t>(z ^ (z >> 31));
    }
};
