// The pair half of contact detection (PairRule.hpp): the overlap decision that skips the
// square root away from contact must give the root's answer.
#include "particles/detection/PairRule.hpp"

#include "core/math/Vec3.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

using regolith::core::Vec3;
using regolith::particles::detection_detail::overlapping;
using regolith::particles::detection_detail::PairSeparation;

TEST(PairRule, OverlapDecisionWithoutRootAgreesWithTheRootAtTheBoundary) {
    // detection_detail::overlapping skips the square root outside a thin band around
    // d^2 = reach^2; its answer must be sqrt(d2) < reach exactly, also for the d2 a few ulps on
    // either side of the rounded reach^2, where a test on d2 alone would be wrong.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> radius(1e-3, 50.0);
    std::size_t inBand = 0, disagreeWithoutRoot = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        double const reach = radius(rng) + radius(rng);
        double d2 = reach * reach;
        for (int k = 0; k < 8; ++k)
            d2 = std::nextafter(d2, 0.0);
        for (int k = 0; k < 17; ++k, d2 = std::nextafter(d2, 1e300)) {
            PairSeparation const s{Vec3::Zero(), Vec3::Zero(), d2, reach};
            bool const exact = std::sqrt(d2) < reach;
            ASSERT_EQ(overlapping(s), exact) << "reach " << reach << " d2 " << d2;
            ++inBand;
            disagreeWithoutRoot += (d2 < reach * reach) != exact ? 1 : 0;
        }
    }
    // The band matters: comparing squares alone gets some of these wrong.
    EXPECT_GT(disagreeWithoutRoot, 0U);
    EXPECT_EQ(inBand, 2000U * 17U);
    // Far from the band, and NaN.
    EXPECT_TRUE(overlapping(PairSeparation{Vec3::Zero(), Vec3::Zero(), 0.0, 1.0}));
    EXPECT_FALSE(overlapping(PairSeparation{Vec3::Zero(), Vec3::Zero(), 1.0 + 1e-9, 1.0}));
    EXPECT_FALSE(overlapping(
        PairSeparation{Vec3::Zero(), Vec3::Zero(), std::numeric_limits<double>::quiet_NaN(), 1.0}));
}
