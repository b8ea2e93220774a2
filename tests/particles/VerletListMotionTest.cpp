// A Verlet list's motion bounds: when it compares the positions with its references, that its
// float references never hide a move of half the skin, which pairs it offers as the copies
// move, and the motion within which no list comes due; the order its classified pairs take; and
// how deep its references stand in the block as the list shifts.
#include "particles/detection/ReferenceDepths.hpp"
#include "particles/detection/VerletList.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;

namespace {

constexpr double kUnknownMotion = std::numeric_limits<double>::infinity();

TEST(VerletList, FloatReferencesNeverHideAMoveOfHalfTheSkin) {
    // Copies far from the origin, where a float reference is off by ~1e-5: each copy moved by
    // exactly skin / 2 from its true reference, in the direction that the rounding shortens
    // (towards the stored reference), must still count as moved; 1 % less must not.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> coordinate(-900.0, 1100.0);
    ParticleStorage ps;
    for (Uid u = 1; u <= 200; ++u)
        ps.add(sphere(u, Vec3(coordinate(rng), coordinate(rng), coordinate(rng)), 0.5, 1.0));
    double const skin = 0.1;
    VerletList list;
    list.restart(ps, skin);
    EXPECT_GT(list.referenceSlack(), 0.0);
    EXPECT_LT(list.referenceSlack(), 0.01 * skin);
    EXPECT_FALSE(list.movedTooFar(ps, kUnknownMotion));
    int hidden = 0; // copies whose stored reference lies off their true one
    for (std::size_t k = 0; k < ps.size(); ++k) {
        Vec3 const truth = ps.position(k);
        Vec3 const stored = list.reference(VerletList::idOf(ps, k));
        EXPECT_LE((stored - truth).norm(), list.referenceSlack()) << "copy " << k;
        if (stored == truth)
            continue;
        ++hidden;
        Vec3 const towards = (stored - truth).normalized();
        ps.position(k) = truth + 0.99 * 0.5 * skin * towards;
        EXPECT_FALSE(list.movedTooFar(ps, kUnknownMotion)) << "copy " << k;
        ps.position(k) = truth + 0.5 * skin * towards;
        EXPECT_TRUE(list.movedTooFar(ps, kUnknownMotion)) << "copy " << k;
        ps.position(k) = truth;
    }
    EXPECT_GT(hidden, 150);
}

/// Eight grains of radius 0.4 on the x axis, one apart.
ParticleStorage rowOfEight() {
    ParticleStorage ps;
    for (Uid u = 1; u <= 8; ++u)
        ps.add(sphere(u, Vec3(double(u), 0.0, 0.0), 0.4, 1.0));
    return ps;
}

TEST(VerletList, MotionBoundsAddUpAndThePositionsAreComparedOnlyOnceTheyReachHalfTheSkin) {
    ParticleStorage ps = rowOfEight();
    double const skin = 0.1;
    VerletList list;
    list.restart(ps, skin);
    // Within the bound the positions are trusted, not compared: a copy moved by a whole skin
    // behind the list's back goes unseen while the bounds given add up to less than skin / 2.
    ps.position(3) += Vec3(skin, 0.0, 0.0);
    EXPECT_FALSE(list.movedTooFar(ps, 0.2 * skin));
    EXPECT_FALSE(list.movedTooFar(ps, 0.2 * skin));
    // 0.6 skin in all: now compared, and the copy's move found.
    EXPECT_TRUE(list.movedTooFar(ps, 0.2 * skin));
    // Back home: the comparison resets the sum to the largest displacement (0), so the next
    // bounds again start from there.
    ps.position(3) -= Vec3(skin, 0.0, 0.0);
    EXPECT_FALSE(list.movedTooFar(ps, kUnknownMotion));
    ps.position(5) += Vec3(0.3 * skin, 0.0, 0.0);
    EXPECT_FALSE(list.movedTooFar(ps, 0.3 * skin));
    ps.position(5) += Vec3(0.3 * skin, 0.0, 0.0);
    EXPECT_TRUE(list.movedTooFar(ps, 0.3 * skin)); // compared: 0.6 skin
    // A negative or NaN bound counts as unknown: compared at once.
    ps.position(5) -= Vec3(0.6 * skin, 0.0, 0.0);
    EXPECT_FALSE(list.movedTooFar(ps, std::nan("")));
    ps.position(2) += Vec3(0.0, 0.7 * skin, 0.0);
    EXPECT_TRUE(list.movedTooFar(ps, -1.0));
}

TEST(VerletList, OffersThePairsTheMotionMayHaveClosedAndNoOther) {
    // The row's neighbours one apart: their surfaces 0.2 apart. Listed with that gap, and one
    // pair of unknown gap, which is always offered.
    ParticleStorage ps = rowOfEight();
    VerletList list;
    list.restart(ps, 0.5);
    for (VerletList::Id k = 0; k + 1 < 8; ++k)
        list.addPair(k, k + 1, VerletList::gapBelow(0.2));
    list.addPair(0, 7);
    auto offered = [&] {
        std::vector<std::size_t> pairs;
        list.forEachNearPair([&](std::size_t, std::size_t, std::size_t p) { pairs.push_back(p); });
        return pairs;
    };
    EXPECT_EQ(offered(), std::vector<std::size_t>{7});
    // Every copy within 0.09 of its reference: no pair 0.2 apart can have closed its gap.
    EXPECT_FALSE(list.movedTooFar(ps, 0.09));
    EXPECT_EQ(offered(), std::vector<std::size_t>{7});
    // Within 0.11: two copies 0.2 apart may now touch; all offered, in list order.
    EXPECT_FALSE(list.movedTooFar(ps, 0.02));
    EXPECT_EQ(offered(), (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7}));
    // A list of near pairs only (a packing's first shell): every pair offered at once.
    list.restart(ps, 0.5);
    for (VerletList::Id k = 0; k + 1 < 8; ++k)
        list.addPair(k, k + 1, VerletList::gapBelow(k == 0 ? 0.2 : 0.01));
    EXPECT_EQ(offered().size(), 7U);
}

TEST(VerletList, ClassifyingPutsTheLeadingPairsFirstEachInTheOrderAdded) {
    // The row's pairs (k, k + 1); the odd ones lead, 4 is parked, 5 keeps its spring. The odd
    // ones listed 0.01 apart, the even ones 0.3 (a quarter skin or more: skipped while the
    // copies move little).
    ParticleStorage ps = rowOfEight();
    VerletList list;
    list.restart(ps, 0.5);
    for (VerletList::Id k = 0; k + 1 < 8; ++k)
        list.addPair(k, k + 1, VerletList::gapBelow(k % 2 == 1 ? 0.01 : 0.3));
    list.classifyFrom(0, [](VerletList::Id& a, VerletList::Id&, CopyImage&) {
        if (a == 4)
            return VerletList::Decision{VerletList::kDrop, false};
        PairMode const mode = a == 5       ? PairMode::Kept
                              : a % 2 == 1 ? PairMode::Owned
                                           : PairMode::Check;
        return VerletList::Decision{static_cast<int>(mode), a % 2 == 1};
    });
    std::vector<std::size_t> firsts;
    std::vector<PairMode> modes;
    list.forEachPair([&](std::size_t a, std::size_t, std::size_t p) {
        firsts.push_back(a);
        modes.push_back(list.mode(p));
    });
    EXPECT_EQ(firsts, (std::vector<std::size_t>{1, 3, 5, 0, 2, 6}));
    EXPECT_EQ(modes, (std::vector<PairMode>{PairMode::Owned, PairMode::Owned, PairMode::Kept,
                                            PairMode::Check, PairMode::Check, PairMode::Check}));
    EXPECT_EQ(list.numOwned(), 3U);
    EXPECT_EQ(list.numKept(), 1U);
    EXPECT_EQ(list.springs().size(), 6U);
    // The gaps went with their pairs: moved 0.02, the pairs 0.01 apart are offered, not the
    // others.
    EXPECT_FALSE(list.movedTooFar(ps, 0.02));
    std::vector<std::size_t> offered;
    list.forEachNearPair([&](std::size_t a, std::size_t, std::size_t) { offered.push_back(a); });
    EXPECT_EQ(offered, (std::vector<std::size_t>{1, 3, 5}));
}

TEST(VerletList, WithinTheQuietMotionNoListComesDue) {
    ParticleStorage ps = rowOfEight();
    double const skin = 0.1;
    VerletList list;
    list.restart(ps, skin);
    // Moves that add up to the quiet motion: never too far, whether the positions are compared
    // (share 0.5) or not; the motion's bound then leaves less room.
    double const quiet = list.quietMotion();
    EXPECT_GT(quiet, 0.49 * skin);
    EXPECT_LT(quiet, list.budget());
    EXPECT_FALSE(list.mayMoveTooFar(quiet));
    ps.position(3) += Vec3(0.5 * quiet, 0.0, 0.0);
    EXPECT_FALSE(list.movedTooFar(ps, 0.5 * quiet, 0.5));
    double const rest = list.quietMotion();
    EXPECT_LT(rest, quiet);
    ps.position(3) += Vec3(rest, 0.0, 0.0);
    EXPECT_FALSE(list.movedTooFar(ps, rest, 0.5));
    // Beyond it the list may come due: here it does.
    ps.position(3) += Vec3(0.02 * skin, 0.0, 0.0);
    EXPECT_TRUE(list.movedTooFar(ps, 0.02 * skin, 0.5));
    // A list without a skin (an empty block's) is due at any motion: no quiet motion.
    list.restart(ps, 0.0);
    EXPECT_EQ(list.quietMotion(), -std::numeric_limits<double>::infinity());
}

TEST(ReferenceDepths, AShiftCountsAgainstTheDepthAlongItsOwnAxis) {
    // Two copies near the block's floor (z = 0.6) and in the middle of x and y: deep along x
    // and y, shallow along z. A shift along x eats the x depth only, so the pair stays deeper
    // than 0.4 along z; the same shift along z does not leave it so.
    ParticleStorage ps;
    ps.add(sphere(1, Vec3(5.0, 5.0, 0.6), 0.5, 1.0));
    ps.add(sphere(2, Vec3(6.0, 5.0, 0.6), 0.5, 1.0));
    VerletList list;
    list.restart(ps, 0.2);
    regolith::core::AABB const block(Vec3::Zero(), Vec3::Constant(10.0));
    ReferenceDepths depths;
    depths.start(list, block, PeriodicFrame{});
    ReferenceDepths::Axes const& a = depths.ofAxes(list, ps, 0);
    EXPECT_DOUBLE_EQ(a[0], 5.0);
    EXPECT_DOUBLE_EQ(a[1], 5.0);
    EXPECT_DOUBLE_EQ(a[2], 0.6);
    EXPECT_DOUBLE_EQ(depths.of(list, ps, 1), 0.6);
    EXPECT_TRUE(depths.unshifted());
    EXPECT_TRUE(depths.deeperThan(list, ps, 0, 1, 0.4));
    depths.setShifted(Vec3(1.5, 0.0, 0.0));
    EXPECT_FALSE(depths.unshifted());
    EXPECT_TRUE(depths.deeperThan(list, ps, 0, 1, 0.4));
    EXPECT_FALSE(depths.deeperThan(list, ps, 0, 1, 3.6)); // 4 - 0.4 left along x
    depths.setShifted(Vec3(0.0, 0.0, 0.3));
    EXPECT_FALSE(depths.deeperThan(list, ps, 0, 1, 0.4));
    EXPECT_TRUE(depths.deeperThan(list, ps, 0, 1, 0.25));
    // Outside the block on one axis: no depth on any.
    ps.add(sphere(3, Vec3(5.0, 11.0, 5.0), 0.5, 1.0));
    list.restart(ps, 0.2);
    depths.start(list, block, PeriodicFrame{});
    ReferenceDepths::Axes const& out = depths.ofAxes(list, ps, 2);
    EXPECT_EQ(out, (ReferenceDepths::Axes{0.0, 0.0, 0.0}));
}

} // namespace
