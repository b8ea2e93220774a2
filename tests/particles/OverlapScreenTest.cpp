// OverlapScreen (the fused contact loop's block-wise overlap test) against the scalar test of
// PairRule.hpp: the same pairs, in the same order, with the same shift bits, in full blocks
// and short ones, near-contact pairs decided by ulps and blocks that overlap whole; and its
// contact-point rule in lanes (ruled) against PairRule's, at ownership points a few ulps from
// the domain's and the region's faces. (The loop's use of both: VerletListTest,
// SameContactsAsCellsScreenedBlockWise.)
#include "particles/detection/OverlapScreen.hpp"

#include "core/math/AABB.hpp"
#include "particles/detection/PairRule.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
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

/// Pairs whose ownership point lies a few ulps from a face: of the domain (x = 0 or 10, y = 0
/// or 10; periodic in x and y, open in z), of `region` (x = 5), or of the point's image
/// beyond (x = 20); in all images, some pairs pressed past the smaller centre (the rule takes
/// that centre), some with both grains Fixed, and some copies three periods out (the lanes
/// leave those to PairRule).
ParticleStorage facePairs(std::size_t pairs, std::uint32_t seed, core::Vec3 const& period) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_int_distribution<int> image(-1, 1);
    ParticleStorage ps;
    double const faces[] = {0.0, 10.0, 5.0, 20.0, -10.0};
    for (std::size_t k = 0; k < pairs; ++k) {
        ParticleInit a, b;
        a.uid = 2 * k + 1;
        b.uid = 2 * k + 2;
        a.radius = 0.3 + 0.2 * u(rng);
        b.radius = k % 5 == 0 ? a.radius : 0.3 + 0.2 * u(rng);
        a.mass = b.mass = 1.0;
        a.flags = b.flags = k % 11 == 0 ? Flags(Flag::Fixed) : Flags();
        a.image = CopyImage{static_cast<std::int8_t>(image(rng)),
                            static_cast<std::int8_t>(image(rng)), 0};
        b.image = CopyImage{static_cast<std::int8_t>(image(rng)),
                            static_cast<std::int8_t>(image(rng)), 0};
        core::Vec3 dir(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        dir.normalize();
        double const reach = a.radius + b.radius;
        double const d = (k % 7 == 0 ? 0.05 : 0.5 + 0.5 * u(rng)) * reach;
        // The point p = x_a + (r_a - pen / 2) dir, moved onto a face on one axis.
        int const axis = static_cast<int>(k % 2);
        double const face = faces[k % 5] + (k % 13 == 0 ? 30.0 : 0.0);
        core::Vec3 xa(10 * u(rng), 10 * u(rng), 10 * u(rng));
        double const toPoint = a.radius - 0.5 * (reach - d);
        xa[axis] = face - toPoint * dir[axis];
        int const ulps = static_cast<int>(rng() % 9) - 4;
        for (int s = 0; s != ulps; s += ulps > 0 ? 1 : -1)
            xa[axis] = std::nextafter(xa[axis], ulps > 0 ? 1e300 : -1e300);
        // Canonical positions: a's local position xa, b's at d dir from it.
        a.position = core::Vec3(xa - imageOffset(a.image, period));
        b.position = core::Vec3(xa + d * dir - imageOffset(b.image, period));
        ps.add(a);
        ps.add(b);
    }
    return ps;
}

TEST(OverlapScreen, RulesInLanesAsPairRuleDoes) {
    core::Vec3 const period(10.0, 10.0, 0.0);
    PeriodicFrame const frame(core::AABB{core::Vec3(0.0, 0.0, 0.0), core::Vec3(10.0, 10.0, 10.0)},
                              {true, true, false});
    ParticleStorage const ps = facePairs(3000, 21, period);
    for (core::AABB const& region :
         {frame.domain, core::AABB{core::Vec3(0.0, 0.0, 0.0), core::Vec3(5.0, 10.0, 10.0)}}) {
        DetectorStats stats;
        detection_detail::PairRule const rule(ps, region, frame, stats);
        OverlapScreen screen;
        std::vector<std::uint32_t> is, js;
        std::size_t decided = 0, unsure = 0, evaluated = 0, fixedKept = 0;
        for (std::size_t first = 0; first < ps.size(); first += 2 * OverlapScreen::kCapacity) {
            is.clear();
            js.clear();
            for (std::size_t k = first;
                 k < std::min(ps.size(), first + 2 * OverlapScreen::kCapacity); k += 2) {
                is.push_back(static_cast<std::uint32_t>(k));
                js.push_back(static_cast<std::uint32_t>(k + 1));
            }
            std::size_t const n = is.size() - (first % 3 == 1 ? 5 : 0); // now and then short
            screen.test(
                ps, period, is.data(), js.data(), n, [](std::size_t, PairOverlap const&) {},
                [&](std::uint64_t overlapping) {
                    std::uint64_t doubtful = 0;
                    std::uint64_t const owned = screen.ruled(ps, region, frame, is.data(),
                                                             js.data(), overlapping, doubtful);
                    EXPECT_EQ(owned & ~overlapping, 0U);
                    EXPECT_EQ(doubtful & ~overlapping, 0U);
                    for (std::uint64_t left = overlapping; left != 0; left &= left - 1) {
                        auto const k = static_cast<std::size_t>(std::countr_zero(left));
                        if ((doubtful >> k) & 1U) {
                            ++unsure;
                            continue;
                        }
                        bool const expected = rule.emitsOverlapping(is[k], js[k]);
                        EXPECT_EQ(((owned >> k) & 1U) != 0, expected) << "pair " << is[k];
                        ++decided;
                        evaluated += expected ? 1 : 0;
                        fixedKept += ps.flags(is[k]).isFixed() && !expected ? 1 : 0;
                    }
                    return overlapping;
                });
        }
        // Every kind was met: decided both ways, Fixed pairs dropped, far copies left to
        // PairRule (which throws for none of them here: three periods out).
        EXPECT_GT(decided, 2000U);
        EXPECT_GT(evaluated, 300U);
        EXPECT_LT(evaluated, decided - 300U);
        EXPECT_GT(fixedKept, 50U);
        EXPECT_GT(unsure, 50U);
    }
}

} // namespace
} // namespace regolith::particles
