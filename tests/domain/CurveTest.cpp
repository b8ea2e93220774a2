// The Hilbert curve (bijective, continuous) and the cut of a weighted curve into per-rank
// chunks (contiguous, balanced within one maximum weight).
#include "core/Error.hpp"
#include "domain/HilbertCurve.hpp"
#include "domain/SfcPartition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

using namespace regolith;
using namespace regolith::domain;

TEST(HilbertCurve, VisitsEveryCellOnceThroughFaceNeighbours) {
    for (int bits = 1; bits <= 4; ++bits) {
        std::uint64_t const cells = std::uint64_t{1} << (3 * bits);
        std::set<std::array<std::uint32_t, 3>> seen;
        std::array<std::uint32_t, 3> previous{};
        for (std::uint64_t i = 0; i < cells; ++i) {
            auto const c = hilbertCell(i, bits);
            for (std::uint32_t const x : c)
                EXPECT_LT(x, std::uint32_t{1} << bits);
            EXPECT_EQ(hilbertIndex(c, bits), i) << "bits " << bits;
            EXPECT_TRUE(seen.insert(c).second) << "cell visited twice";
            if (i > 0) {
                int manhattan = 0;
                for (int a = 0; a < 3; ++a)
                    manhattan += std::abs(static_cast<int>(c[a]) - static_cast<int>(previous[a]));
                EXPECT_EQ(manhattan, 1) << "jump at " << i << " (bits " << bits << ")";
            }
            previous = c;
        }
        EXPECT_EQ(seen.size(), cells);
        EXPECT_EQ(hilbertCell(0, bits), (std::array<std::uint32_t, 3>{0, 0, 0}));
    }
}

TEST(HilbertCurve, RoundTripsOnLargeGrids) {
    std::mt19937_64 rng(5);
    for (int bits : {10, 21}) {
        std::uniform_int_distribution<std::uint32_t> coord(0, (std::uint32_t{1} << bits) - 1);
        for (int i = 0; i < 1000; ++i) {
            std::array<std::uint32_t, 3> const c{coord(rng), coord(rng), coord(rng)};
            std::uint64_t const h = hilbertIndex(c, bits);
            EXPECT_LT(h, std::uint64_t{1} << (3 * bits));
            EXPECT_EQ(hilbertCell(h, bits), c);
        }
    }
}

TEST(HilbertCurve, EnclosingGridAndLimits) {
    EXPECT_EQ(hilbertBitsFor({1, 1, 1}), 0);
    EXPECT_EQ(hilbertBitsFor({2, 1, 1}), 1);
    EXPECT_EQ(hilbertBitsFor({3, 1, 1}), 2);
    EXPECT_EQ(hilbertBitsFor({4, 4, 4}), 2);
    EXPECT_EQ(hilbertBitsFor({1, 1, 100}), 7);
    EXPECT_EQ(hilbertIndex({0, 0, 0}, 0), 0U);
    EXPECT_THROW((void)hilbertIndex({0, 0, 0}, kMaxHilbertBits + 1), core::Error);
    EXPECT_THROW((void)hilbertCell(0, -1), core::Error);
}

namespace {

/// The least largest load of any cut of `w` into `parts` contiguous pieces, by dynamic
/// programming over all cuts (small inputs only).
double bruteBottleneck(std::vector<double> const& w, int parts) {
    std::size_t const n = w.size();
    double const inf = std::numeric_limits<double>::infinity();
    // best[k][i]: the least largest load of the first i elements in k pieces
    std::vector<std::vector<double>> best(static_cast<std::size_t>(parts) + 1,
                                          std::vector<double>(n + 1, inf));
    best[0][0] = 0.0;
    for (std::size_t k = 1; k <= static_cast<std::size_t>(parts); ++k)
        for (std::size_t i = 0; i <= n; ++i)
            for (std::size_t j = 0; j <= i; ++j) {
                double piece = 0.0;
                for (std::size_t m = j; m < i; ++m)
                    piece += w[m];
                best[k][i] = std::min(best[k][i], std::max(best[k - 1][j], piece));
            }
    return best[static_cast<std::size_t>(parts)][n];
}

/// The loads of the parts of `owner`.
std::vector<double> loadsOf(std::vector<double> const& w, std::vector<int> const& owner,
                            int parts) {
    std::vector<double> load(static_cast<std::size_t>(parts), 0.0);
    for (std::size_t i = 0; i < w.size(); ++i)
        load[static_cast<std::size_t>(owner[i])] += w[i];
    return load;
}

/// Checks owners are contiguous, in range, and the largest load is within the maximum weight
/// of the mean. Returns the number of ranks that got at least one element.
int checkPartition(std::vector<double> const& w, std::vector<int> const& owner, int parts) {
    EXPECT_EQ(owner.size(), w.size());
    double total = 0.0;
    double wmax = 0.0;
    for (double const x : w) {
        total += x;
        wmax = std::max(wmax, x);
    }
    std::set<int> used;
    for (std::size_t i = 0; i < w.size(); ++i) {
        EXPECT_GE(owner[i], 0);
        EXPECT_LT(owner[i], parts);
        if (i > 0) {
            EXPECT_LE(owner[i - 1], owner[i]) << "not contiguous at " << i;
        }
        used.insert(owner[i]);
    }
    if (total > 0.0) {
        std::vector<double> const load = loadsOf(w, owner, parts);
        EXPECT_LE(*std::max_element(load.begin(), load.end()) - total / parts, wmax * (1.0 + 1e-12))
            << parts << " parts, " << w.size() << " elements";
    }
    return static_cast<int>(used.size());
}

} // namespace

TEST(SfcPartition, RandomWeightsAreBalancedWithinOneMaximumWeight) {
    std::mt19937_64 rng(99);
    for (int trial = 0; trial < 300; ++trial) {
        int const n = std::uniform_int_distribution<int>(0, 400)(rng);
        int const parts = std::uniform_int_distribution<int>(1, 33)(rng);
        double const spread = std::pow(10.0, std::uniform_real_distribution<double>(0, 4)(rng));
        std::vector<double> w(static_cast<std::size_t>(n));
        for (double& x : w) // some zeros, the rest spanning `spread`
            x = std::uniform_int_distribution<int>(0, 9)(rng) == 0
                    ? 0.0
                    : std::uniform_real_distribution<double>(1.0, spread)(rng);
        checkPartition(w, partitionCurve(w, parts), parts);
    }
}

TEST(SfcPartition, ReachesTheLeastLargestLoad) {
    // Blocks coarse against a rank's share (a few per rank, weights spanning a factor 30, as
    // a pile among empty blocks): the largest load equals the best over all cuts.
    std::mt19937_64 rng(11);
    for (int trial = 0; trial < 400; ++trial) {
        int const n = std::uniform_int_distribution<int>(1, 24)(rng);
        int const parts = std::uniform_int_distribution<int>(1, 9)(rng);
        std::vector<double> w(static_cast<std::size_t>(n));
        for (double& x : w)
            x = std::uniform_int_distribution<int>(0, 3)(rng) == 0
                    ? 1.0
                    : std::uniform_real_distribution<double>(1.0, 30.0)(rng);
        std::vector<int> const owner = partitionCurve(w, parts);
        checkPartition(w, owner, parts);
        std::vector<double> const load = loadsOf(w, owner, parts);
        EXPECT_NEAR(*std::max_element(load.begin(), load.end()), bruteBottleneck(w, parts), 1e-9)
            << "trial " << trial << ": " << n << " elements, " << parts << " parts";
    }
}

TEST(SfcPartition, EqualWeightsAndIdleRanks) {
    std::vector<double> const ten(10, 2.5);
    auto const owner = partitionCurve(ten, 3); // 10 / 3: chunks of 3 or 4
    EXPECT_EQ(checkPartition(ten, owner, 3), 3);
    std::vector<double> const two(2, 1.0);
    EXPECT_EQ(checkPartition(two, partitionCurve(two, 8), 8), 2); // six ranks idle
    std::vector<double> const zeros(5, 0.0); // no load information: count the blocks
    auto const z = partitionCurve(zeros, 5);
    EXPECT_EQ(z, (std::vector<int>{0, 1, 2, 3, 4}));
    std::vector<double> const heavy{1, 1, 100, 1, 1}; // one block outweighs the rest
    // The midpoints leave a rank idle; relieving the part of the two last blocks uses it.
    EXPECT_EQ(checkPartition(heavy, partitionCurve(heavy, 4), 4), 4);
}

TEST(SfcPartition, RelievesAPartTheMidpointsOverload) {
    // Empty blocks (weight 1) before a settled pile (10 each), as a load that fell to the
    // floor: the midpoints give the parts 18, 30, 20, 20; one heavy block moved across the
    // first cut gives 28, 20, 20, 20, the least largest load any cut reaches.
    std::vector<double> w(8, 1.0);
    w.insert(w.end(), 8, 10.0);
    std::vector<int> const owner = partitionCurve(w, 4);
    checkPartition(w, owner, 4);
    EXPECT_EQ(loadsOf(w, owner, 4), (std::vector<double>{28.0, 20.0, 20.0, 20.0}));
}

TEST(SfcPartition, RejectsBadWeightsAndRankCounts) {
    std::vector<double> const negative{1.0, -1.0};
    EXPECT_THROW((void)partitionCurve(negative, 2), core::InputError);
    std::vector<double> const nan{1.0, std::numeric_limits<double>::quiet_NaN()};
    EXPECT_THROW((void)partitionCurve(nan, 2), core::InputError);
    std::vector<double> const inf{std::numeric_limits<double>::infinity()};
    EXPECT_THROW((void)partitionCurve(inf, 2), core::InputError);
    EXPECT_THROW((void)partitionCurve(negative, 0), core::InputError);
}
