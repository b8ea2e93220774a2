// forEachWithFlags (particles/sync/CopyScan.hpp), the eight-bytes-at-a-time walk over flag
// bytes behind round 2 and the force reduction: checked against a byte-by-byte loop on random
// flags, for one-bit and several-bit masks and lengths that leave every possible tail.
#include "particles/sync/CopyScan.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace regolith::particles;

namespace {

template <std::uint8_t kMask>
void expectSameAsPlainLoop(std::vector<Flags> const& flags) {
    std::vector<std::size_t> expected;
    for (std::size_t i = 0; i < flags.size(); ++i)
        if ((flags[i].bits() & kMask) == kMask)
            expected.push_back(i);
    std::vector<std::size_t> visited;
    sync_detail::forEachWithFlags<kMask>(flags, [&](std::size_t i) { visited.push_back(i); });
    EXPECT_EQ(visited, expected) << "mask " << int{kMask} << ", " << flags.size() << " bytes";
}

} // namespace

TEST(CopyScan, ForEachWithFlagsVisitsExactlyTheBytesHoldingTheMask) {
    std::mt19937 rng(7);
    constexpr std::uint8_t kShadow = Flags(Flag::Shadow).bits();
    constexpr std::uint8_t kSpreadingShadow = Flags(Flag::Shadow | Flag::Spreads).bits();
    constexpr std::uint8_t kFixedShadow = Flags(Flag::Shadow | Flag::Fixed).bits();
    for (std::size_t n = 0; n <= 41; ++n) {
        for (int density = 0; density < 3; ++density) {
            // Sparse, half and dense: words with no hit, some and all.
            std::bernoulli_distribution bit(density == 0 ? 0.05 : (density == 1 ? 0.5 : 0.95));
            std::vector<Flags> flags(n);
            for (Flags& f : flags)
                for (Flag const k : {Flag::Shadow, Flag::Fixed, Flag::Global, Flag::Spreads})
                    if (bit(rng))
                        f = f | k;
            expectSameAsPlainLoop<kShadow>(flags);
            expectSameAsPlainLoop<kSpreadingShadow>(flags);
            expectSameAsPlainLoop<kFixedShadow>(flags);
        }
    }
}
