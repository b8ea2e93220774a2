// The cells' candidate sweep, one by one and in lanes (where the build and the processor have
// AVX-512), against its definition: the same pairs, in the same order, with the same squared
// distances, bit for bit, for cells with one grain to many and ranges shorter and longer than a
// lane block, and a cell with more hits than the lanes collect before appending them.
#include "particles/detection/CellCandidates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace regolith::particles::cells_detail {
namespace {

struct Slots {
    std::vector<float> x, y, z, radius;
    [[nodiscard]] SphereLanes lanes() const {
        return {x.data(), y.data(), z.data(), radius.data()};
    }
};

/// `n` spheres in a box of edge `edge`, radii in [0.3, 0.5] (in the 3 x 3 x 3 box about a tenth
/// of the pairs within reach; in a box of edge 0.3, whose diagonal is shorter than 0.6, every
/// pair).
Slots sample(std::size_t n, std::uint32_t seed, float edge = 3.0F) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> at(0.0F, edge);
    std::uniform_real_distribution<float> r(0.3F, 0.5F);
    Slots s;
    for (std::size_t k = 0; k < n; ++k) {
        s.x.push_back(at(rng));
        s.y.push_back(at(rng));
        s.z.push_back(at(rng));
        s.radius.push_back(r(rng));
    }
    return s;
}

/// The definition: own pairs (t > s), then each forward range, s by s, t ascending.
std::vector<SlotPair> scalarSweep(Slots const& s, SlotRange own,
                                  std::vector<SlotRange> const& forward, double slack) {
    std::vector<SlotPair> out;
    auto each = [&](std::uint32_t t0, std::uint32_t t1) {
        for (std::uint32_t a = own.begin; a < own.end; ++a)
            for (std::uint32_t t = std::max(t0, a + 1); t < t1; ++t) {
                double const dx = double{s.x[t]} - double{s.x[a]};
                double const dy = double{s.y[t]} - double{s.y[a]};
                double const dz = double{s.z[t]} - double{s.z[a]};
                double const d2 = dx * dx + dy * dy + dz * dz;
                double const reach = double{s.radius[a]} + double{s.radius[t]} + slack;
                if (d2 < reach * reach)
                    out.push_back({a, t, d2});
            }
    };
    each(own.begin, own.end);
    for (SlotRange const& r : forward)
        each(r.begin, r.end);
    return out;
}

TEST(CellCandidates, SweepsACellAsTheScalarDefinitionInOrderAndBitForBit) {
    double const slack = 0.01;
    std::size_t hits = 0;
    for (std::uint32_t members : {1U, 2U, 3U, 8U, 9U, 17U}) {
        for (std::uint32_t seed = 1; seed <= 5; ++seed) {
            Slots const s = sample(200, seed * 31 + members);
            // The cell, then forward ranges of 0 to 20 slots (lane blocks of eight and a rest).
            SlotRange const own{10, 10 + members};
            std::vector<SlotRange> forward;
            std::uint32_t next = own.end;
            for (std::uint32_t length : {1U, 0U, 7U, 8U, 9U, 20U}) {
                forward.push_back({next, next + length});
                next += length + 3;
            }
            forward.push_back({190, 200}); // up to the arrays' end, not a multiple of eight
            std::vector<SlotPair> const want = scalarSweep(s, own, forward, slack);
            std::vector<std::vector<SlotPair>> paths(2);
            appendCellOverlapsOneByOne(s.lanes(), own, forward, slack, paths[0]);
            CellScratch scratch;
            if (cellLanesAvailable())
                appendCellOverlapsInLanes(s.lanes(), own, forward, slack, scratch, paths[1]);
            else
                paths.pop_back();
            for (std::vector<SlotPair> const& got : paths) {
                ASSERT_EQ(got.size(), want.size()) << members << " members, seed " << seed;
                for (std::size_t k = 0; k < want.size(); ++k) {
                    EXPECT_EQ(got[k].s, want[k].s);
                    EXPECT_EQ(got[k].t, want[k].t);
                    EXPECT_EQ(got[k].d2, want[k].d2); // bit for bit: the same operations
                }
            }
            hits += want.size();
        }
    }
    EXPECT_GT(hits, 300U); // the comparisons had pairs to compare
}

TEST(CellCandidates, SweepsACrowdedCellWithMoreHitsThanTheLanesCollectAtOnce) {
    // 300 spheres in a box of edge 0.3, every pair within reach: 39,900 hits, appended in rounds
    // (the lanes collect about a thousand before appending them).
    Slots const s = sample(300, 5, 0.3F);
    SlotRange const own{0, 200};
    std::vector<SlotRange> const forward{{200, 300}};
    std::vector<SlotPair> const want = scalarSweep(s, own, forward, 0.0);
    ASSERT_EQ(want.size(), 200U * 199U / 2U + 200U * 100U);
    std::vector<SlotPair> got;
    CellScratch scratch;
    appendCellOverlaps(s.lanes(), own, forward, 0.0, scratch, got);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t k = 0; k < want.size(); ++k) {
        ASSERT_EQ(got[k].s, want[k].s) << k;
        ASSERT_EQ(got[k].t, want[k].t) << k;
        ASSERT_EQ(got[k].d2, want[k].d2) << k;
    }
}

TEST(CellCandidates, UsesTheLanesWhereTheBuildAndTheProcessorHaveThem) {
#ifdef REGOLITH_CELL_LANES_BUILT
    EXPECT_TRUE(cellLanesCompiled()); // the lane file got the lane code generation
#else
    EXPECT_FALSE(cellLanesCompiled());
#endif
    __builtin_cpu_init();
    bool const processor = __builtin_cpu_supports("avx512f") != 0 &&
                           __builtin_cpu_supports("avx512vl") != 0 &&
                           __builtin_cpu_supports("avx512dq") != 0;
    EXPECT_EQ(cellLanesAvailable(), cellLanesCompiled() && processor);
}

/// Both paths' pairs of the slots of `s` as one cell (no forward range).
std::vector<std::vector<SlotPair>> bothPaths(Slots const& s, double slack) {
    std::vector<std::vector<SlotPair>> paths(1);
    SlotRange const own{0, static_cast<std::uint32_t>(s.x.size())};
    appendCellOverlapsOneByOne(s.lanes(), own, {}, slack, paths[0]);
    if (cellLanesAvailable()) {
        CellScratch scratch;
        appendCellOverlapsInLanes(s.lanes(), own, {}, slack, scratch, paths.emplace_back());
    }
    return paths;
}

TEST(CellCandidates, ExactlyTouchingIsNotAPair) {
    // Slots 1 and 2 exactly r_0 + r_t from slot 0 (1 along x; 5 along (3, 4, 0)): d2 equals
    // reach^2 in double, and the test is strict. Slot 3 is 2.5 away.
    Slots s;
    auto add = [&](float x, float y, float r) {
        s.x.push_back(x);
        s.y.push_back(y);
        s.z.push_back(0.0F);
        s.radius.push_back(r);
    };
    add(0.0F, 0.0F, 2.0F);
    add(-3.0F, 0.0F, 1.0F);
    add(3.0F, 4.0F, 3.0F);
    add(0.0F, 2.5F, 0.25F);
    for (auto const& got : bothPaths(s, 0.0))
        EXPECT_TRUE(got.empty()) << got.size() << " pairs";
    // A hair of slack makes both touching pairs, not the third.
    for (auto const& got : bothPaths(s, std::ldexp(1.0, -40))) {
        ASSERT_EQ(got.size(), 2U);
        EXPECT_EQ(got[0].t, 1U);
        EXPECT_EQ(got[1].t, 2U);
        EXPECT_EQ(got[1].d2, 25.0);
    }
}

TEST(CellCandidates, AppendsAfterWhatTheListHolds) {
    Slots const s = sample(40, 7);
    std::vector<SlotPair> got{{99, 100, 1.5}};
    CellScratch scratch;
    std::vector<SlotRange> const forward{{5, 40}};
    appendCellOverlaps(s.lanes(), {0, 5}, forward, 0.0, scratch, got);
    ASSERT_GT(got.size(), 1U);
    EXPECT_EQ(got[0].s, 99U);
    EXPECT_EQ(got[0].d2, 1.5);
}

} // namespace
} // namespace regolith::particles::cells_detail
