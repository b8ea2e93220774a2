// Philox4x32-10 against Random123's known-answer vectors, the documented (seed, uid, stream)
// mapping, statistical sanity (5 sigma) and independence of keys, and rank independence.
#include "core/random/CounterRng.hpp"

#include "core/mpi/Comm.hpp"
#include "core/random/Philox.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <utility>
#include <vector>

using namespace regolith::core;
using namespace regolith::core::random;

namespace {

// Random123 kat_vectors, "philox4x32 10" lines: counter, key -> output.
struct Kat {
    PhiloxCounter counter;
    PhiloxKey key;
    PhiloxCounter expected;
};
constexpr Kat kKats[] = {
    {{0, 0, 0, 0}, {0, 0}, {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
    {{0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
     {0xffffffff, 0xffffffff},
     {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
    {{0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
     {0xa4093822, 0x299f31d0},
     {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
};

// The block function is constexpr: the known answers hold at compile time too.
static_assert(philox4x32(kKats[0].counter, kKats[0].key) == kKats[0].expected);
static_assert(philox4x32(kKats[2].counter, kKats[2].key) == kKats[2].expected);
static_assert(std::uniform_random_bit_generator<CounterRng>);

/// Mean and (population) variance of n draws.
template <class Draw>
std::pair<double, double> moments(int n, Draw draw) {
    double sum = 0.0;
    double sumSq = 0.0;
    for (int i = 0; i < n; ++i) {
        double const x = draw();
        sum += x;
        sumSq += x * x;
    }
    double const mean = sum / n;
    return {mean, sumSq / n - mean * mean};
}

/// Pearson correlation of n pairs.
template <class Draw>
double correlation(int n, Draw draw) {
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (int i = 0; i < n; ++i) {
        auto const [x, y] = draw();
        sx += x;
        sy += y;
        sxx += x * x;
        syy += y * y;
        sxy += x * y;
    }
    double const cov = sxy / n - (sx / n) * (sy / n);
    return cov / std::sqrt((sxx / n - (sx / n) * (sx / n)) * (syy / n - (sy / n) * (sy / n)));
}

} // namespace

TEST(Philox, KnownAnswerVectorsFromRandom123) {
    for (auto const& kat : kKats)
        EXPECT_EQ(philox4x32(kat.counter, kat.key), kat.expected);
}

TEST(CounterRng, MappingOfSeedUidStreamToPhiloxIsAsDocumented) {
    std::uint64_t const seed = 0x0123456789abcdefull;
    std::uint64_t const uid = 0xfedcba9876543210ull;
    CounterRng rng(seed, uid, 7);
    PhiloxKey const key{0x89abcdef, 0x01234567};
    for (std::uint32_t block = 0; block < 3; ++block) {
        auto const w = philox4x32({block, 7, 0x76543210, 0xfedcba98}, key);
        EXPECT_EQ(rng.next(), w[0] | std::uint64_t{w[1]} << 32) << "block " << block;
        EXPECT_EQ(rng.next(), w[2] | std::uint64_t{w[3]} << 32) << "block " << block;
    }
    EXPECT_EQ(rng.blocksUsed(), 3u);
}

TEST(CounterRng, SameKeySameNumbersDifferentKeyDifferentNumbers) {
    CounterRng a(5, 100);
    CounterRng b(5, 100);
    CounterRng otherUid(5, 101);
    CounterRng otherSeed(6, 100);
    CounterRng otherStream(5, 100, 1);
    int same = 0;
    for (int i = 0; i < 1000; ++i) {
        std::uint64_t const x = a.next();
        EXPECT_EQ(x, b.next());
        same += (x == otherUid.next()) + (x == otherSeed.next()) + (x == otherStream.next());
    }
    EXPECT_EQ(same, 0);
}

TEST(CounterRng, UniformMomentsWithinFiveSigma) {
    constexpr int n = 1'000'000;
    CounterRng rng(2024, 17);
    double lo = 1.0;
    double hi = 0.0;
    auto const [mean, var] = moments(n, [&] {
        double const u = rng.uniform();
        lo = std::min(lo, u);
        hi = std::max(hi, u);
        return u;
    });
    EXPECT_GE(lo, 0.0);
    EXPECT_LT(hi, 1.0);
    // U(0,1): mean 1/2, variance 1/12; sd of the sample mean sqrt(1/12/n), of the sample
    // variance sqrt((1/80 - 1/144)/n) = sqrt(1/(180 n)).
    EXPECT_NEAR(mean, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
    EXPECT_NEAR(var, 1.0 / 12.0, 5.0 * std::sqrt(1.0 / 180.0 / n));

    CounterRng ab(2024, 18);
    auto const [meanAb, varAb] = moments(n, [&] {
        double const x = ab.uniform(-2.0, 6.0);
        EXPECT_TRUE(x >= -2.0 && x < 6.0);
        return x;
    });
    EXPECT_NEAR(meanAb, 2.0, 5.0 * 8.0 * std::sqrt(1.0 / 12.0 / n));
    EXPECT_NEAR(varAb, 64.0 / 12.0, 5.0 * 64.0 * std::sqrt(1.0 / 180.0 / n));
}

TEST(CounterRng, NormalMomentsWithinFiveSigma) {
    constexpr int n = 1'000'000;
    CounterRng rng(7, 123456789);
    auto const [mean, var] = moments(n, [&] { return rng.normal(); });
    // N(0,1): sd of the sample mean 1/sqrt(n), of the sample variance sqrt(2/n).
    EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(n));
    EXPECT_NEAR(var, 1.0, 5.0 * std::sqrt(2.0 / n));

    CounterRng shifted(7, 123456790);
    auto const [m2, v2] = moments(n, [&] { return shifted.normal(3.0, 0.5); });
    EXPECT_NEAR(m2, 3.0, 5.0 * 0.5 / std::sqrt(n));
    EXPECT_NEAR(v2, 0.25, 5.0 * 0.25 * std::sqrt(2.0 / n));
}

TEST(CounterRng, NeighbouringKeysAreUncorrelated) {
    constexpr int n = 200'000;
    double const bound = 5.0 / std::sqrt(n); // sd of a sample correlation of independent pairs
    CounterRng u0(1, 1000), u1(1, 1001);
    EXPECT_LT(std::abs(correlation(n,
                                   [&] {
                                       return std::pair{u0.uniform(), u1.uniform()};
                                   })),
              bound)
        << "adjacent uids";
    CounterRng s0(1, 1000), s1(2, 1000);
    EXPECT_LT(std::abs(correlation(n,
                                   [&] {
                                       return std::pair{s0.uniform(), s1.uniform()};
                                   })),
              bound)
        << "adjacent seeds";
    CounterRng t0(1, 1000, 0), t1(1, 1000, 1);
    EXPECT_LT(std::abs(correlation(n,
                                   [&] {
                                       return std::pair{t0.uniform(), t1.uniform()};
                                   })),
              bound)
        << "adjacent streams";
    CounterRng lag(3, 3);
    double previous = lag.uniform();
    EXPECT_LT(std::abs(correlation(n,
                                   [&] {
                                       double const x = lag.uniform();
                                       return std::pair{std::exchange(previous, x), x};
                                   })),
              bound)
        << "lag-1 within one stream";

    // The first draw of consecutive uids (one number per particle) is uniform too.
    std::uint64_t uid = 0;
    auto const [mean, var] = moments(n, [&] { return CounterRng(9, uid++).uniform(); });
    EXPECT_NEAR(mean, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
    EXPECT_NEAR(var, 1.0 / 12.0, 5.0 * std::sqrt(1.0 / 180.0 / n));
}

TEST(CounterRng, DrawsDoNotDependOnWhichRankMakesThem) {
    // uids dealt round-robin to the ranks; the sum (mod 2^64) of their draws must equal the
    // serial sum over all uids, whatever the number of ranks.
    Comm world;
    constexpr std::uint64_t kUids = 4096;
    auto draws = [](std::uint64_t uid) {
        CounterRng rng(77, uid, 3);
        return rng.next() + rng.next() * 3 + rng.next() * 5;
    };
    std::uint64_t local = 0;
    for (std::uint64_t uid = static_cast<std::uint64_t>(world.rank()); uid < kUids;
         uid += static_cast<std::uint64_t>(world.size()))
        local += draws(uid);
    std::uint64_t serial = 0;
    for (std::uint64_t uid = 0; uid < kUids; ++uid)
        serial += draws(uid);
    EXPECT_EQ(world.allReduce(local, ReduceOp::Sum), serial);
}
