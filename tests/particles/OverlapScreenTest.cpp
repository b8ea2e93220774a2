// OverlapScreen (the fused contact loop's block-wise overlap test) against the scalar test of
// PairRule.hpp: the same pairs, in the same order, with the same shift bits, in full blocks
// and short ones, near-contact pairs decided by ulps and blocks that overlap whole. (Ruling on
// the pairs near a face is the loop's: VerletListTest, SameContactsAsCellsScreenedBlockWise.)
#include "particles/detection/OverlapScreen.hpp"

#include "particles/detection/PairRule.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

namespace regolith::particles {
namespace {

struct Handed {
    std::size_t i = 0, j = 0;
    core::Vec3 shift = core::Vec3::Zero();
    std::size_t at = 0; ///< the pair's place in the sequence tested
};

bool sameBits(core::Vec3 const& a, core::Vec3 const& b) {
    return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

/// Copies in a periodic box of period 10: pairs at random distances, many a few ulps from
/// touching, with images -maxImage..maxImage on each axis.
ParticleStorage copies(std::size_t n, std::uint32_t seed, int maxImage = 1) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_int_distribution<int> image(-maxImage, maxImage);
    ParticleStorage ps;
    for (std::size_t k = 0; k < n; ++k) {
        ParticleInit p;
        p.uid = k + 1;
        p.radius = 0.3 + 0.2 * u(rng);
        p.mass = 1.0;
        p.position = core::Vec3(10 * u(rng), 10 * u(rng), 10 * u(rng));
        p.image =
            CopyImage{static_cast<std::int8_t>(image(rng)), static_cast<std::int8_t>(image(rng)),
                      static_cast<std::int8_t>(image(rng))};
        ps.add(p);
    }
    return ps;
}

/// Pairs (i, i + 1) placed at the reach give or take a few ulps (in the canonical frame),
/// each followed by an (i, random) pair that mostly misses; and runs of deeply overlapping
/// pairs that make whole blocks overlap.
std::vector<std::pair<std::size_t, std::size_t>> pairsOf(ParticleStorage& ps,
                                                         core::Vec3 const& period) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (std::size_t i = 0; i + 1 < ps.size(); i += 2) {
        std::size_t const j = i + 1;
        bool const deep = (i / 128) % 3 == 1; // runs of deep overlaps: whole blocks touch
        core::Vec3 dir(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        dir.normalize();
        double d = ps.radius(i) + ps.radius(j);
        if (deep) {
            d *= 0.5;
        } else {
            int const ulps = static_cast<int>(i % 9) - 4;
            for (int k = 0; k != ulps; k += ulps > 0 ? 1 : -1)
                d = std::nextafter(d, ulps > 0 ? 1e300 : 0.0);
        }
        // x_j + shiftJ - x_i = d * dir in i's frame.
        core::Vec3 const shift =
            imageOffset(detection_detail::imageDifference(ps.image(j), ps.image(i)), period);
        ps.position(j) = core::Vec3(ps.position(i) + d * dir - shift);
        pairs.emplace_back(i, j);
        // Deep runs list their pair twice, so that whole blocks overlap.
        pairs.emplace_back(i, deep ? j : static_cast<std::size_t>(u(rng) * (ps.size() - 1)));
    }
    return pairs;
}

/// What the scalar test of PairRule.hpp finds among `pairs`, in order.
std::vector<Handed> scalarOverlaps(ParticleStorage const& ps, core::Vec3 const& period,
                                   std::vector<std::pair<std::size_t, std::size_t>> const& pairs) {
    std::vector<Handed> out;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        auto const [i, j] = pairs[p];
        auto const s = detection_detail::separation(ps, i, j, period);
        if (detection_detail::overlapping(s))
            out.push_back({i, j, s.shiftJ, p});
    }
    return out;
}

/// What the screen hands on, in blocks as the list hands them over: mostly full, now and then
/// a short one. `counted`: the sum of the blocks' counts.
std::vector<Handed> screened(ParticleStorage const& ps, core::Vec3 const& period,
                             std::vector<std::pair<std::size_t, std::size_t>> const& pairs,
                             bool oneImage, std::size_t& counted) {
    std::vector<Handed> got;
    OverlapScreen screen;
    counted = 0;
    std::vector<std::uint32_t> is, js;
    for (std::size_t first = 0; first < pairs.size();) {
        std::size_t const n = std::min<std::size_t>(first % 7 == 3 ? 17 : OverlapScreen::kCapacity,
                                                    pairs.size() - first);
        is.clear();
        js.clear();
        for (std::size_t k = 0; k < n; ++k) {
            is.push_back(static_cast<std::uint32_t>(pairs[first + k].first));
            js.push_back(static_cast<std::uint32_t>(pairs[first + k].second));
        }
        counted += screen.test(
            ps, period, is.data(), js.data(), n,
            [&](std::size_t k, PairOverlap const& o) {
                got.push_back({o.i, o.j, o.shiftJ, first + k});
            },
            oneImage);
        first += n;
    }
    return got;
}

/// Whether `got` and `expected` hold the same pairs, places and shift bits; returns how many
/// of them are the near-contact pairs (i, i + 1).
std::size_t expectSame(std::vector<Handed> const& got, std::vector<Handed> const& expected) {
    EXPECT_EQ(got.size(), expected.size());
    std::size_t borderline = 0;
    for (std::size_t k = 0; k < std::min(got.size(), expected.size()); ++k) {
        EXPECT_EQ(got[k].i, expected[k].i) << k;
        EXPECT_EQ(got[k].j, expected[k].j) << k;
        EXPECT_EQ(got[k].at, expected[k].at) << k;
        EXPECT_TRUE(sameBits(got[k].shift, expected[k].shift)) << k;
        borderline += got[k].j == got[k].i + 1 ? 1 : 0;
    }
    return borderline;
}

TEST(OverlapScreen, HandsOnWhatTheScalarTestFindsInOrderWithTheSameShifts) {
    core::Vec3 const period(10.0, 10.0, 10.0);
    ParticleStorage ps = copies(4000, 9);
    auto const pairs = pairsOf(ps, period);
    std::vector<Handed> const expected = scalarOverlaps(ps, period, pairs);
    std::size_t counted = 0;
    std::vector<Handed> const got = screened(ps, period, pairs, false, counted);
    EXPECT_EQ(counted, expected.size());
    // Both regimes were exercised: near-contact pairs decided by ulps, and deep runs.
    EXPECT_GT(expectSame(got, expected), 500U);
    EXPECT_LT(expected.size(), pairs.size() * 3 / 4);
    EXPECT_GT(expected.size(), pairs.size() / 3);
}

TEST(OverlapScreen, PairsInOneImageScreenedWithoutTheirImagesAsWithThem) {
    // Every copy in image zero (the Kept pairs' case): told so, the screen skips the images and
    // hands on the same pairs with the same zero shifts, +0.0 on every axis.
    core::Vec3 const period(10.0, 10.0, 10.0);
    ParticleStorage ps = copies(4000, 5, 0);
    auto const pairs = pairsOf(ps, period);
    std::vector<Handed> const expected = scalarOverlaps(ps, period, pairs);
    std::size_t counted = 0;
    std::vector<Handed> const got = screened(ps, period, pairs, true, counted);
    EXPECT_EQ(counted, expected.size());
    EXPECT_GT(expectSame(got, expected), 500U);
    for (Handed const& h : got)
        EXPECT_TRUE(sameBits(h.shift, core::Vec3::Zero()));
    EXPECT_GT(expected.size(), pairs.size() / 3);
}

} // namespace
} // namespace regolith::particles
