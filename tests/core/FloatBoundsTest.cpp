// floatNotBelow / floatNotAbove: the float on the safe side of a double, compared with the
// definition through std::nextafter over random doubles of every magnitude and the edges
// (zeros, subnormals, the largest float, infinities, NaN).
#include "core/math/FloatBounds.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace {

using regolith::core::floatNotAbove;
using regolith::core::floatNotBelow;

float nextAfterBelow(double x) {
    auto const f = static_cast<float>(x);
    return static_cast<double>(f) >= x || std::isnan(x)
               ? f
               : std::nextafter(f, std::numeric_limits<float>::infinity());
}

float nextAfterAbove(double x) {
    auto const f = static_cast<float>(x);
    return static_cast<double>(f) <= x || std::isnan(x)
               ? f
               : std::nextafter(f, -std::numeric_limits<float>::infinity());
}

std::uint32_t bitsOf(float f) {
    return std::bit_cast<std::uint32_t>(f);
}

void expectBounds(double x) {
    float const below = floatNotBelow(x), above = floatNotAbove(x);
    EXPECT_EQ(bitsOf(below), bitsOf(nextAfterBelow(x))) << "floatNotBelow(" << x << ")";
    EXPECT_EQ(bitsOf(above), bitsOf(nextAfterAbove(x))) << "floatNotAbove(" << x << ")";
    if (!std::isnan(x)) {
        EXPECT_GE(static_cast<double>(below), x);
        EXPECT_LE(static_cast<double>(above), x);
    }
}

TEST(FloatBounds, MatchNextAfterAtTheEdges) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    double const fmax = std::numeric_limits<float>::max();
    double const tiny = std::numeric_limits<float>::denorm_min();
    std::vector<double> const edges{0.0,    -0.0,    tiny, -tiny, 0.3 * tiny,   -0.3 * tiny,
                                    1e-300, -1e-300, fmax, -fmax, fmax * 1.001, -fmax * 1.001,
                                    1e300,  -1e300,  inf,  -inf,  1.0 / 3.0,    -1.0 / 3.0,
                                    0.1,    -0.1,    1.0,  -1.0};
    for (double const x : edges)
        expectBounds(x);
    EXPECT_TRUE(std::isnan(floatNotBelow(std::numeric_limits<double>::quiet_NaN())));
    EXPECT_TRUE(std::isnan(floatNotAbove(std::numeric_limits<double>::quiet_NaN())));
    // Below a positive double that rounds up to a float: strictly below, one float down.
    EXPECT_LT(floatNotAbove(0.1), 0.1F);
    EXPECT_EQ(floatNotBelow(0.1), 0.1F);
}

TEST(FloatBounds, MatchNextAfterOnRandomDoubles) {
    std::mt19937_64 rng(20261204);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-160, 140);
    int stepped = 0;
    for (int k = 0; k < 200000; ++k) {
        double const x = std::ldexp(mantissa(rng), exponent(rng));
        expectBounds(x);
        stepped += static_cast<double>(static_cast<float>(x)) != x ? 1 : 0;
    }
    EXPECT_GT(stepped, 100000); // most doubles are not floats: the step is exercised
}

} // namespace
