// OverlapScreen (the fused contact loop's block-wise overlap test) against the scalar test of
// PairRule.hpp: the same pairs, in the same order, with the same shift bits, whether the
// screen tests in lanes or (while whole blocks overlap) pair by pair; a pair offered as ruled
// only where the full contact-point rule emits it.
#include "particles/detection/OverlapScreen.hpp"

#include "particles/detection/PairRule.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <gtest/gtest.h>

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
    std::uint8_t* hint = nullptr;
};

bool sameBits(core::Vec3 const& a, core::Vec3 const& b) {
    return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

/// Copies in a periodic box of period 10: pairs at random distances, many a few ulps from
/// touching, with images -1..1 on each axis.
ParticleStorage copies(std::size_t n, std::uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_int_distribution<int> image(-1, 1);
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
        // Deep runs offer their pair twice, so that whole blocks overlap (the direct mode).
        pairs.emplace_back(i, deep ? j : static_cast<std::size_t>(u(rng) * (ps.size() - 1)));
    }
    return pairs;
}

TEST(OverlapScreen, HandsOnWhatTheScalarTestFindsInOrderWithTheSameShifts) {
    core::Vec3 const period(10.0, 10.0, 10.0);
    ParticleStorage ps = copies(4000, 9);
    auto const pairs = pairsOf(ps, period);
    std::vector<std::uint8_t> hints(pairs.size(), 0);

    std::vector<Handed> expected;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        auto const [i, j] = pairs[p];
        auto const s = detection_detail::separation(ps, i, j, period);
        if (detection_detail::overlapping(s))
            expected.push_back({i, j, s.shiftJ, &hints[p]});
    }

    std::vector<Handed> got;
    auto onPair = [&](PairOverlap const& o, std::uint8_t& hint) {
        got.push_back({o.i, o.j, o.shiftJ, &hint});
    };
    OverlapScreen screen;
    std::size_t counted = 0;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        counted +=
            screen.offer(ps, period, pairs[p].first, pairs[p].second, hints[p], nullptr, onPair);
        if (p % 1000 == 999) // a pair that bypasses the screen flushes it first
            counted += screen.flush(ps, period, onPair);
    }
    counted += screen.flush(ps, period, onPair);

    ASSERT_EQ(got.size(), expected.size());
    EXPECT_EQ(counted, expected.size());
    std::size_t borderline = 0;
    for (std::size_t k = 0; k < got.size(); ++k) {
        EXPECT_EQ(got[k].i, expected[k].i) << k;
        EXPECT_EQ(got[k].j, expected[k].j) << k;
        EXPECT_EQ(got[k].hint, expected[k].hint) << k;
        EXPECT_TRUE(sameBits(got[k].shift, expected[k].shift)) << k;
        borderline += got[k].j == got[k].i + 1 ? 1 : 0;
    }
    // Both regimes were exercised: near-contact pairs decided by ulps, and deep runs.
    EXPECT_GT(borderline, 500U);
    EXPECT_LT(expected.size(), pairs.size() * 3 / 4);
    EXPECT_GT(expected.size(), pairs.size() / 3);
}

TEST(OverlapScreen, HandsOnARuledPairOnlyWhereTheContactPointRuleEmitsIt) {
    // Every third pair in canonical order is ruled (as PairMode::Check pairs are): the block
    // is half of the periodic box, and half of the copies are Fixed, so that the rule drops
    // many overlapping pairs, for either reason.
    core::Vec3 const period(10.0, 10.0, 10.0);
    ParticleStorage ps = copies(4000, 11);
    for (std::size_t k = 0; k < ps.size(); k += 3) // image zero: the block holds their points
        ps.setImage(k, kNoImage);                  // where they lie in its half of the domain
    auto const pairs = pairsOf(ps, period);
    for (std::size_t k = 0; k < ps.size(); k += 4) { // pairs (k, k + 1) both Fixed
        ps.setFlags(k, Flag::Fixed);
        ps.setFlags(k + 1, Flag::Fixed);
    }
    PeriodicFrame const frame(core::AABB{core::Vec3::Zero(), period}, {true, true, true});
    core::AABB const block{core::Vec3::Zero(), core::Vec3(5.0, 10.0, 10.0)};
    DetectorStats stats;
    detection_detail::PairRule const rule(ps, block, frame, stats);
    std::vector<std::uint8_t> hints(pairs.size(), 0);
    auto const ruled = [&](std::size_t p) {
        return p % 3 == 0 && ps.uid(pairs[p].first) < ps.uid(pairs[p].second);
    };

    std::vector<Handed> expected;
    std::size_t overlapping = 0, dropped = 0, droppedFixed = 0, emittedRuled = 0;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        auto const [i, j] = pairs[p];
        auto const s = detection_detail::separation(ps, i, j, period);
        if (!detection_detail::overlapping(s))
            continue;
        ++overlapping;
        Contact c;
        if (ruled(p) && !rule(i, j, c)) {
            ++dropped;
            droppedFixed += ps.flags(i).isFixed() && ps.flags(j).isFixed() ? 1 : 0;
            continue;
        }
        emittedRuled += ruled(p) ? 1 : 0;
        expected.push_back({i, j, s.shiftJ, &hints[p]});
    }

    std::vector<Handed> got;
    auto onPair = [&](PairOverlap const& o, std::uint8_t& hint) {
        got.push_back({o.i, o.j, o.shiftJ, &hint});
    };
    OverlapScreen screen(&rule);
    std::size_t counted = 0;
    for (std::size_t p = 0; p < pairs.size(); ++p)
        counted += screen.offer(ps, period, pairs[p].first, pairs[p].second, hints[p], nullptr,
                                onPair, ruled(p));
    counted += screen.flush(ps, period, onPair);

    ASSERT_EQ(got.size(), expected.size());
    EXPECT_EQ(counted, overlapping); // a ruled pair that overlaps counts, emitted or not
    for (std::size_t k = 0; k < got.size(); ++k) {
        EXPECT_EQ(got[k].i, expected[k].i) << k;
        EXPECT_EQ(got[k].j, expected[k].j) << k;
        EXPECT_EQ(got[k].hint, expected[k].hint) << k;
        EXPECT_TRUE(sameBits(got[k].shift, expected[k].shift)) << k;
    }
    // The rule dropped ruled pairs for both reasons (two Fixed grains; the ownership point in
    // another block or image instance) and emitted others.
    EXPECT_GT(droppedFixed, 10U);
    EXPECT_GT(dropped - droppedFixed, 100U);
    EXPECT_GT(emittedRuled, 50U);
}

} // namespace
} // namespace regolith::particles
