// LinkedCells against brute force: the single-precision sphere copies may report pairs up to
// roundingSlack() beyond touching, but never miss a pair that touches in double precision,
// never report one twice, and the same for the ball queries of forEachOverlapWith.
#include "particles/detection/LinkedCells.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace regolith::particles {
namespace {

struct Spheres {
    std::vector<core::Vec3> x;
    std::vector<double> r;
    std::vector<std::uint32_t> members;
};

/// n spheres in a box of edge `extent` at `offset`, radii in [0.3, 0.5]; half of them are
/// placed at exactly the reach (r_a + r_b + slack, give or take a few ulps) from the one
/// before, so that the rounding of the copies decides.
Spheres sample(std::size_t n, double extent, double offset, double slack, std::uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Spheres s;
    for (std::size_t k = 0; k < n; ++k) {
        double const r = 0.3 + 0.2 * u(rng);
        core::Vec3 x(offset + extent * u(rng), offset + extent * u(rng), offset + extent * u(rng));
        if (k % 2 == 1) {
            core::Vec3 dir(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
            dir.normalize();
            double d = s.r.back() + r + slack;
            for (int ulps = static_cast<int>(k % 7) - 3; ulps != 0; ulps += ulps > 0 ? -1 : 1)
                d = std::nextafter(d, ulps > 0 ? 1e300 : 0.0);
            x = s.x.back() + d * dir;
        }
        s.x.push_back(x);
        s.r.push_back(r);
        s.members.push_back(static_cast<std::uint32_t>(k));
    }
    return s;
}

double gap(Spheres const& s, std::size_t a, std::size_t b, double slack) {
    return (s.x[a] - s.x[b]).norm() - (s.r[a] + s.r[b] + slack);
}

bool touches(Spheres const& s, std::size_t a, std::size_t b, double slack) {
    double const reach = s.r[a] + s.r[b] + slack;
    return (s.x[a] - s.x[b]).squaredNorm() < reach * reach;
}

/// `extent`: the box's edge; `edge`: the cells' (at least the reach, 2 * 0.5 + slack).
void checkPairs(double offset, double extent = 20.0, double edge = 1.05) {
    double const slack = 0.05;
    Spheres const s = sample(3000, extent, offset, slack, 7);
    LinkedCells cells;
    cells.build(s.x, s.r, s.members, edge, 8 * s.x.size(), slack);
    EXPECT_GT(cells.roundingSlack(), 0.0);
    std::set<std::pair<std::size_t, std::size_t>> found;
    cells.forEachOverlap([&](std::size_t a, std::size_t b) {
        auto const key = std::minmax(a, b);
        EXPECT_TRUE(found.insert({key.first, key.second}).second) << a << " " << b << " twice";
        EXPECT_LE(gap(s, a, b, slack), 2 * cells.roundingSlack()) << a << " " << b;
    });
    std::size_t touching = 0;
    for (std::size_t a = 0; a < s.x.size(); ++a)
        for (std::size_t b = a + 1; b < s.x.size(); ++b)
            if (touches(s, a, b, slack)) {
                ++touching;
                EXPECT_TRUE(found.count({a, b})) << "missed " << a << " " << b;
            }
    EXPECT_GT(touching, 500U); // most of the borderline half: those a few ulps inside
}

TEST(LinkedCells, FindsEveryTouchingPairDespiteSinglePrecisionCopies) {
    checkPairs(0.0);
}

TEST(LinkedCells, FindsEveryTouchingPairFarFromTheOrigin) {
    checkPairs(1.0e4); // coordinates where a float's ulp (1e-3) exceeds the ulp-sized gaps
}

TEST(LinkedCells, FindsEveryTouchingPairInCrowdedCells) {
    // Hundreds of members per cell: the candidates are tested in chunks, not one by one.
    checkPairs(0.0, 6.0, 3.0);
}

/// forEachOverlap's `apart`: a pair it puts apart is at least that far apart, one that
/// touches it does not put apart, and for those apart the bound is not far below the truth
/// (radii 0.3-0.5: at least 0.57 of it). In sparse rows (one by one) and crowded cells
/// (chunks).
void checkApart(double extent, double edge) {
    double const slack = 0.05;
    Spheres const s = sample(3000, extent, 0.0, slack, 5);
    LinkedCells cells;
    cells.build(s.x, s.r, s.members, edge, 8 * s.x.size(), slack);
    std::size_t apart = 0, tight = 0;
    cells.forEachOverlap([&](std::size_t a, std::size_t b, double atLeast) {
        double const surfaces = gap(s, a, b, 0.0);
        if (atLeast > 0.0) {
            EXPECT_LE(atLeast, surfaces) << a << " " << b;
        }
        if (surfaces < 0.0) {
            EXPECT_LE(atLeast, 0.0) << a << " " << b;
        }
        if (surfaces > 0.01) {
            ++apart;
            tight += atLeast > 0.5 * surfaces ? 1 : 0;
        }
    });
    EXPECT_GT(apart, 200U);
    EXPECT_EQ(tight, apart);
}

TEST(LinkedCells, ReportsALowerBoundOnHowFarApartAPairIs) {
    checkApart(20.0, 1.05);
    checkApart(6.0, 3.0);
}

TEST(LinkedCells, BallQueryFindsEveryTouchingMember) {
    double const slack = 0.02;
    Spheres const s = sample(2000, 15.0, 1.0e3, slack, 11);
    LinkedCells cells;
    cells.build(s.x, s.r, s.members, 2 * 0.5 + slack, 8 * s.x.size(), slack);
    for (std::size_t q = 1; q < s.x.size(); q += 2) { // each one touches sphere q - 1
        std::set<std::size_t> found;
        cells.forEachOverlapWith(s.x[q], s.r[q], [&](std::size_t b) {
            EXPECT_TRUE(found.insert(b).second);
            EXPECT_LE(gap(s, q, b, slack), 2 * cells.roundingSlack());
        });
        for (std::size_t b = 0; b < s.x.size(); ++b) {
            if (touches(s, q, b, slack)) {
                EXPECT_TRUE(found.count(b)) << "query " << q << " missed " << b;
            }
        }
    }
}

} // namespace
} // namespace regolith::particles
