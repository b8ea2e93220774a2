// LinkedCells whose grid wraps along periodic axes against brute force over the images: every
// pair instance (a, b, shift) that touches is reported exactly once, with b's shift, also where
// an axis holds only one or two cells; and the ball queries find every touching image.
#include "particles/detection/LinkedCells.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <tuple>
#include <vector>

namespace regolith::particles {
namespace {

struct Box {
    core::Vec3 min, max;
    std::array<bool, 3> wrapped;
};

core::Vec3 periodOf(Box const& box) {
    core::Vec3 p = core::Vec3::Zero();
    for (int a = 0; a < 3; ++a)
        if (box.wrapped[static_cast<std::size_t>(a)])
            p[a] = box.max[a] - box.min[a];
    return p;
}

using Instance = std::tuple<std::uint32_t, std::uint32_t, int, int, int>;

/// The instance with a < b: (b, a, -shift) is (a, b, shift).
Instance canonical(std::uint32_t a, std::uint32_t b, CopyImage const& s) {
    if (a < b)
        return {a, b, s[0], s[1], s[2]};
    return {b, a, -s[0], -s[1], -s[2]};
}

void checkWrapped(Box const& box, std::size_t n, double edge, std::uint32_t seed) {
    double const slack = 0.05;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<core::Vec3> x;
    std::vector<double> r;
    std::vector<std::uint32_t> members;
    for (std::size_t k = 0; k < n; ++k) {
        core::Vec3 p;
        for (int a = 0; a < 3; ++a)
            p[a] = box.min[a] + (box.max[a] - box.min[a]) * u(rng);
        x.push_back(p);
        r.push_back(0.3 + 0.2 * u(rng));
        members.push_back(static_cast<std::uint32_t>(k));
    }
    LinkedCells::Wrap wrap;
    wrap.axes = box.wrapped;
    wrap.min = box.min;
    wrap.max = box.max;
    LinkedCells cells;
    cells.build(x, r, members, edge, 8 * n + 64, slack, wrap);
    core::Vec3 const period = periodOf(box);
    auto distance = [&](std::uint32_t a, std::uint32_t b, CopyImage const& s) {
        return (localPosition(x[b], s, period) - x[a]).norm();
    };
    std::set<Instance> found;
    cells.forEachOverlap([&](std::uint32_t a, std::uint32_t b, double, CopyImage s) {
        EXPECT_FALSE(a == b && isZero(s));
        EXPECT_TRUE(found.insert(canonical(a, b, s)).second) << a << " " << b << " twice";
        EXPECT_LE(distance(a, b, s) - (r[a] + r[b] + slack), 2 * cells.roundingSlack());
    });
    // Brute force: every image within two periods on the wrapped axes.
    std::size_t touching = 0;
    int const reachX = box.wrapped[0] ? 2 : 0, reachY = box.wrapped[1] ? 2 : 0,
              reachZ = box.wrapped[2] ? 2 : 0;
    for (std::uint32_t a = 0; a < n; ++a)
        for (std::uint32_t b = a; b < n; ++b)
            for (int i = -reachX; i <= reachX; ++i)
                for (int j = -reachY; j <= reachY; ++j)
                    for (int k = -reachZ; k <= reachZ; ++k) {
                        CopyImage const s{static_cast<std::int8_t>(i), static_cast<std::int8_t>(j),
                                          static_cast<std::int8_t>(k)};
                        if (a == b &&
                            (isZero(s) || i < 0 || (i == 0 && (j < 0 || (j == 0 && k < 0)))))
                            continue; // a grain with itself: each image pair once
                        if (!(distance(a, b, s) < r[a] + r[b] + slack))
                            continue;
                        ++touching;
                        if (a == b)
                            continue; // a grain's own images: the caller drops them
                        EXPECT_TRUE(found.count(canonical(a, b, s)))
                            << "missed " << a << " " << b << " " << i << " " << j << " " << k;
                    }
    EXPECT_GT(touching, n / 4);
    // Ball queries: every member image the ball touches, once.
    for (std::uint32_t q = 0; q < n; q += 7) {
        std::set<Instance> seen;
        cells.forEachOverlapWith(x[q], r[q], [&](std::uint32_t b, CopyImage s) {
            EXPECT_TRUE(seen.insert({q, b, s[0], s[1], s[2]}).second);
        });
        for (std::uint32_t b = 0; b < n; ++b)
            for (int i = -reachX; i <= reachX; ++i)
                for (int j = -reachY; j <= reachY; ++j)
                    for (int k = -reachZ; k <= reachZ; ++k) {
                        CopyImage const s{static_cast<std::int8_t>(i), static_cast<std::int8_t>(j),
                                          static_cast<std::int8_t>(k)};
                        if (distance(q, b, s) < r[q] + r[b] + slack) {
                            EXPECT_TRUE(seen.count({q, b, i, j, k}))
                                << "query " << q << " missed " << b << " " << i << " " << j << " "
                                << k;
                        }
                    }
    }
}

TEST(LinkedCellsWrap, FindsEveryPairInstanceAcrossWrappedFaces) {
    checkWrapped({core::Vec3(0, 0, 0), core::Vec3(8, 7, 6), {true, true, false}}, 600, 1.05, 3);
    checkWrapped({core::Vec3(-3, 1, 2), core::Vec3(5, 9, 8.5), {true, true, true}}, 600, 1.05, 5);
}

TEST(LinkedCellsWrap, OneOrTwoCellsAlongAWrappedAxis) {
    // 1.5 and 2.5 cell edges: one and two cells, where a pair meets in several images.
    checkWrapped({core::Vec3(0, 0, 0), core::Vec3(1.6, 6, 2.5), {true, false, true}}, 120, 1.05, 9);
    checkWrapped({core::Vec3(0, 0, 0), core::Vec3(2.2, 2.2, 2.2), {true, true, true}}, 60, 1.05,
                 11);
}

TEST(LinkedCellsWrap, ACellBudgetBelowTheGhostLayersStillBuilds) {
    // One grain, a budget of one cell: the grid still takes its 3 cells per wrapped axis.
    std::vector<core::Vec3> const x{core::Vec3(0.2, 0.2, 0.2)};
    std::vector<double> const r{0.5};
    std::vector<std::uint32_t> const members{0};
    LinkedCells::Wrap wrap;
    wrap.axes = {true, true, true};
    wrap.min = core::Vec3::Zero();
    wrap.max = core::Vec3::Constant(3.0);
    LinkedCells cells;
    cells.build(x, r, members, 1.05, 1, 0.0, wrap);
    std::vector<CopyImage> hits;
    cells.forEachOverlapWith(core::Vec3(2.9, 2.9, 2.9), 0.5,
                             [&](std::uint32_t, CopyImage s) { hits.push_back(s); });
    ASSERT_EQ(hits.size(), 1U);
    EXPECT_EQ(hits[0], (CopyImage{1, 1, 1}));
}

} // namespace
} // namespace regolith::particles
