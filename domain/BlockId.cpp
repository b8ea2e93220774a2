#include "domain/BlockId.hpp"

#include "core/Error.hpp"

#include <bit>
#include <ostream>

namespace regolith::domain {

BlockId BlockId::root(std::uint64_t rootIndex) {
    if (rootIndex > kMaxRootIndex)
        throw core::Error("BlockId::root: root index " + std::to_string(rootIndex) +
                          " exceeds the maximum " + std::to_string(kMaxRootIndex));
    return fromRaw((rootIndex << kPathBits) | std::uint64_t{1});
}

bool BlockId::isValid() const {
    std::uint64_t const path = pathWord();
    // The marker must sit at a multiple of 3 bits: 3 * level.
    return path != 0 && (std::bit_width(path) - 1) % 3 == 0;
}

int BlockId::level() const {
    return (static_cast<int>(std::bit_width(pathWord())) - 1) / 3;
}

int BlockId::octantAt(int l) const {
    int const shift = 3 * (level() - l);
    return static_cast<int>((pathWord() >> shift) & 7U);
}

BlockId BlockId::parent() const {
    if (level() == 0)
        throw core::Error("BlockId::parent: " + toString() + " is a root block");
    std::uint64_t const path = pathWord() >> 3;
    return fromRaw((m_raw & ~((std::uint64_t{1} << kPathBits) - 1)) | path);
}

BlockId BlockId::child(int k) const {
    if (k < 0 || k > 7)
        throw core::Error("BlockId::child: octant " + std::to_string(k) + " not in [0, 7]");
    if (level() >= kMaxLevel)
        throw core::Error("BlockId::child: " + toString() + " is at the deepest level " +
                          std::to_string(kMaxLevel));
    std::uint64_t const path = (pathWord() << 3) | static_cast<std::uint64_t>(k);
    return fromRaw((m_raw & ~((std::uint64_t{1} << kPathBits) - 1)) | path);
}

bool BlockId::isAncestorOf(BlockId other) const {
    if (rootIndex() != other.rootIndex())
        return false;
    int const l = level();
    int const lo = other.level();
    if (lo < l)
        return false;
    return (other.pathWord() >> (3 * (lo - l))) == pathWord();
}

std::string BlockId::toString() const {
    std::string s = std::to_string(rootIndex());
    int const l = level();
    for (int i = 1; i <= l; ++i) {
        s += '.';
        s += static_cast<char>('0' + octantAt(i));
    }
    return s;
}

std::strong_ordering operator<=>(BlockId a, BlockId b) {
    if (auto const c = a.rootIndex() <=> b.rootIndex(); c != 0)
        return c;
    // Align both paths (without marker) to the deepest level: equal aligned paths mean one is
    // an ancestor of the other, and the ancestor (lower level) comes first.
    int const la = a.level();
    int const lb = b.level();
    auto const aligned = [](BlockId id, int l) {
        std::uint64_t const digits = id.pathWord() & ((std::uint64_t{1} << (3 * l)) - 1);
        return digits << (3 * (BlockId::kMaxLevel - l));
    };
    if (auto const c = aligned(a, la) <=> aligned(b, lb); c != 0)
        return c;
    return la <=> lb;
}

std::ostream& operator<<(std::ostream& os, BlockId id) {
    return os << id.toString();
}

} // namespace regolith::domain
