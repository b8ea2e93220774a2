// Particle storage: uids, flags and the SoA container with its uid map (the history and the
// map itself: ContactHistoryTest.cpp, CopyIndexTest.cpp).
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;
using regolith::core::Error;
using regolith::core::InputError;

TEST(Uid, PacksRankAndCounterAndRejectsOverflow) {
    Uid const u = makeUid(123, 456789);
    EXPECT_EQ(uidRank(u), 123);
    EXPECT_EQ(uidCounter(u), 456789U);
    EXPECT_EQ(makeUid(1, 0), Uid{1} << 40);
    EXPECT_LT(makeUid(0, kUidCounterMask), makeUid(1, 0)); // orders by rank, then counter
    EXPECT_THROW((void)makeUid(-1, 0), Error);
    EXPECT_THROW((void)makeUid(kGlobalObjectRank + 1, 0), Error);
    EXPECT_THROW((void)makeUid(0, kUidCounterMask + 1), Error);
    EXPECT_THROW((void)makeUid(kGlobalObjectRank, kUidCounterMask), Error); // == kInvalidUid
    // Rolling-spring keys are nobody's uid: the ranks they would take create none.
    EXPECT_THROW((void)makeUid(kFirstReservedRank, 0), Error);
    EXPECT_THROW((void)makeUid(kGlobalObjectRank - 1, 0), Error);
    for (Uid const id : {makeUid(0, 0), makeUid(kFirstReservedRank - 1, kUidCounterMask),
                         makeUid(kGlobalObjectRank, 0), makeUid(kGlobalObjectRank, 7)}) {
        EXPECT_EQ(rollingKey(rollingKey(id)), id);
        int const rank = uidRank(rollingKey(id));
        EXPECT_TRUE(rank >= kFirstReservedRank && rank < kGlobalObjectRank) << rank;
    }

    UidGenerator gen(5, 10);
    EXPECT_EQ(gen.next(), makeUid(5, 10));
    EXPECT_EQ(gen.next(), makeUid(5, 11));
    EXPECT_EQ(gen.nextCounter(), 12U);
    // Walls live in the reserved rank field: never equal to a particle's uid.
    EXPECT_EQ(uidRank(wallUid(3)), kGlobalObjectRank);
}

TEST(Flags, SetAndTest) {
    Flags f;
    EXPECT_TRUE(f.isMaster());
    f.set(Flag::Shadow).set(Flag::Fixed);
    EXPECT_TRUE(f.isShadow() && f.isFixed() && !f.isGlobal());
    f.set(Flag::Shadow, false);
    EXPECT_TRUE(f.isMaster() && f.isFixed());
    EXPECT_EQ(Flag::Fixed | Flag::Global, Flags(Flag::Global).set(Flag::Fixed));
}

TEST(ParticleStorage, InversesFollowMassRadiusAndFixedFlag) {
    ParticleStorage ps;
    auto const i = ps.add(sphere(7, Vec3::Zero(), 0.5, 2.0));
    EXPECT_DOUBLE_EQ(ps.invMass(i), 0.5);
    EXPECT_DOUBLE_EQ(ps.invInertia(i), 1.0 / (0.4 * 2.0 * 0.25));
    ps.setMass(i, 4.0);
    ps.setRadius(i, 1.0);
    EXPECT_DOUBLE_EQ(ps.invInertia(i), 1.0 / (0.4 * 4.0));
    ps.setFlags(i, Flag::Fixed);
    EXPECT_EQ(ps.invMass(i), 0.0);
    EXPECT_EQ(ps.invInertia(i), 0.0);
    EXPECT_THROW(ps.add(sphere(7, Vec3::Zero(), 1.0, 1.0)), Error);
    EXPECT_THROW(ps.add(sphere(kInvalidUid, Vec3::Zero(), 1.0, 1.0)), Error);
    EXPECT_EQ(ps.size(), 1U);
}

TEST(ParticleStorage, RandomAddRemoveKeepsUidMapConsistent) {
    // A std::map from uid to the particle's data is the model; 20,000 random operations
    // (add, remove by index, remove by uid, also of absent uids), full comparison every 50.
    struct Record {
        Vec3 position;
        double mass;
        Flags flags;
        Uid partner; // one history entry per particle travels with it too
    };
    std::map<Uid, Record> model;
    ParticleStorage ps;
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    UidGenerator gen(3);

    auto check = [&] {
        ASSERT_EQ(ps.size(), model.size());
        std::size_t masters = 0;
        for (auto const& [uid, rec] : model) {
            auto const i = ps.find(uid);
            ASSERT_NE(i, ParticleStorage::kNotFound);
            EXPECT_EQ(ps.uid(i), uid);
            EXPECT_EQ(ps.position(i), rec.position);
            EXPECT_EQ(ps.mass(i), rec.mass);
            EXPECT_EQ(ps.invMass(i), rec.flags.isFixed() ? 0.0 : 1.0 / rec.mass);
            EXPECT_EQ(ps.flags(i), rec.flags);
            ASSERT_EQ(ps.history(i).size(), 1U);
            EXPECT_EQ(ps.history(i).entries()[0].partner, rec.partner);
            masters += rec.flags.isMaster() ? 1 : 0;
        }
        for (std::size_t i = 0; i < ps.size(); ++i)
            EXPECT_EQ(ps.find(ps.uid(i)), i);
        EXPECT_EQ(ps.countMasters(), masters);
        std::size_t visited = 0;
        ps.forEachMaster([&](std::size_t i) {
            EXPECT_TRUE(ps.flags(i).isMaster());
            ++visited;
        });
        EXPECT_EQ(visited, masters);
    };

    for (int op = 0; op < 20000; ++op) {
        double const r = u(rng);
        if (r < 0.5 || ps.empty()) {
            Uid const uid = gen.next();
            ParticleInit p = sphere(uid, Vec3(u(rng), u(rng), u(rng)), 0.1, 1.0 + u(rng));
            if (u(rng) < 0.3)
                p.flags = Flag::Shadow;
            if (u(rng) < 0.1)
                p.flags = p.flags | Flag::Fixed;
            auto const i = ps.add(p);
            Uid const partner = uid + 1000000;
            ps.history(i).touch(partner, 1);
            model[uid] = Record{p.position, p.mass, p.flags, partner};
        } else if (r < 0.8) {
            auto const i = static_cast<std::size_t>(u(rng) * static_cast<double>(ps.size()));
            model.erase(ps.uid(i));
            ps.remove(i);
        } else {
            // Remove by uid: an existing one, or one never added.
            bool const existing = u(rng) < 0.7;
            Uid const uid = existing ? std::next(model.begin(),
                                                 static_cast<std::ptrdiff_t>(u(rng) * model.size()))
                                           ->first
                                     : makeUid(4, op);
            EXPECT_EQ(ps.removeUid(uid), existing);
            model.erase(uid);
        }
        if (op % 50 == 0)
            check();
    }
    check();
    EXPECT_GT(ps.bytes(), ps.size() * (6 * sizeof(Vec3)));
    ps.clear();
    EXPECT_TRUE(ps.empty());
    EXPECT_EQ(ps.find(model.begin()->first), ParticleStorage::kNotFound);
}

TEST(ParticleStorage, PermuteMovesEveryPropertyAndTheMap) {
    ParticleStorage ps;
    for (Uid u = 0; u < 6; ++u) {
        auto const i =
            ps.add(sphere(100 + u, Vec3(static_cast<double>(u), 0, 0), 0.1 * (u + 1), 1.0 + u));
        ps.history(i).touch(200 + u, 1);
        ps.shadowHolders(i).push_back(CopyRef{static_cast<int>(u), u, kNoImage});
    }
    std::vector<std::size_t> const order{3, 0, 5, 1, 4, 2};
    ps.permute(order);
    for (std::size_t k = 0; k < order.size(); ++k) {
        Uid const u = order[k];
        EXPECT_EQ(ps.uid(k), 100 + u);
        EXPECT_EQ(ps.find(100 + u), k);
        EXPECT_EQ(ps.position(k).x(), static_cast<double>(u));
        EXPECT_DOUBLE_EQ(ps.radius(k), 0.1 * (u + 1));
        EXPECT_DOUBLE_EQ(ps.invMass(k), 1.0 / (1.0 + u));
        ASSERT_EQ(ps.history(k).size(), 1U);
        EXPECT_EQ(ps.history(k).entries()[0].partner, 200 + u);
        EXPECT_EQ(ps.shadowHolders(k).at(0).block, u);
    }
    EXPECT_THROW(ps.permute(std::vector<std::size_t>{0, 1, 2}), Error);
    EXPECT_THROW(ps.permute(std::vector<std::size_t>{0, 1, 2, 3, 4, 4}), Error);
    EXPECT_EQ(ps.uid(0), 103U); // unchanged by the refused calls
}

TEST(ParticleStorage, KeepsOrientationsOnlyOnceOneDiffersFromTheIdentity) {
    using regolith::core::Quat;
    Quat const turned(Eigen::AngleAxisd(0.3, Vec3(0, 0, 1)));
    Quat const tilted(Eigen::AngleAxisd(0.7, Vec3(1, 0, 0)));
    ParticleStorage ps;
    for (Uid u = 1; u <= 4; ++u)
        ps.add(sphere(u, Vec3(static_cast<double>(u), 0, 0), 0.1, 1.0));
    ps.setOrientation(1, Quat::Identity()); // no change: still none stored
    EXPECT_FALSE(ps.storesOrientations());
    std::size_t const without = ps.bytes();
    EXPECT_EQ(ps.orientation(2).coeffs(), Quat::Identity().coeffs());

    ParticleInit p = sphere(5, Vec3(5, 0, 0), 0.1, 1.0);
    p.orientation = turned;
    ps.add(p); // the first one that differs: every copy gets one
    EXPECT_TRUE(ps.storesOrientations());
    EXPECT_GE(ps.bytes(), without + 5 * sizeof(Quat));
    ps.setOrientation(0, tilted);
    ps.add(sphere(6, Vec3(6, 0, 0), 0.1, 1.0)); // identity, now stored too
    ASSERT_EQ(ps.size(), 6U);
    std::vector<Quat> const expected{tilted,           Quat::Identity(), Quat::Identity(),
                                     Quat::Identity(), turned,           Quat::Identity()};
    for (std::size_t i = 0; i < ps.size(); ++i)
        EXPECT_EQ(ps.orientation(i).coeffs(), expected[i].coeffs()) << "copy " << i;

    ps.remove(0);                                        // the last copy (uid 6) moves into slot 0
    ps.permute(std::vector<std::size_t>{4, 0, 1, 2, 3}); // uid 5 first
    EXPECT_EQ(ps.uid(0), 5U);
    EXPECT_EQ(ps.orientation(0).coeffs(), turned.coeffs());
    EXPECT_EQ(ps.orientation(ps.find(6)).coeffs(), Quat::Identity().coeffs());

    ps.clear(); // empty again: back to none stored
    ps.add(sphere(7, Vec3::Zero(), 0.1, 1.0));
    EXPECT_FALSE(ps.storesOrientations());
    ParticleStorage empty; // the first copy of a storage may bring an orientation too
    p.uid = 8;
    empty.add(p);
    EXPECT_EQ(empty.orientation(0).coeffs(), turned.coeffs());
    Quat const signedZero(1.0, -0.0, 0.0, 0.0); // == the identity, but other bits
    ps.setOrientation(0, signedZero);           // (a shadow must get its master's bits)
    EXPECT_TRUE(ps.storesOrientations());
    EXPECT_TRUE(std::signbit(ps.orientation(0).x()));
}

TEST(WallList, NormalisesAndRejectsBadNormals) {
    WallList walls;
    auto const k = walls.add(Vec3(0, 0, 1), Vec3(0, 0, 2));
    EXPECT_EQ(walls[k].geometry.normal, Vec3::UnitZ());
    EXPECT_EQ(walls[k].uid, wallUid(0));
    EXPECT_DOUBLE_EQ(walls[k].distance(Vec3(5, 5, 3)), 2.0);
    EXPECT_THROW(walls.add(Vec3::Zero(), Vec3::Zero()), InputError);
    EXPECT_THROW(walls.add(Vec3::Zero(), Vec3(std::nan(""), 0, 1)), InputError);
    EXPECT_EQ(walls.size(), 1U);
}

namespace regolith::particles {
namespace {

/// A sphere of radius 0.5, mass 1 and uid 7 at the origin: a master at image zero.
ParticleInit grainSeven() {
    ParticleInit p;
    p.uid = 7;
    p.radius = 0.5;
    p.mass = 1.0;
    return p;
}

TEST(ParticleStorage, OneUidAtSeveralPeriodicImages) {
    ParticleStorage ps;
    ParticleInit p = grainSeven();
    ps.add(p);
    p.image = CopyImage{1, 0, 0};
    p.flags = Flag::Shadow;
    std::size_t const image = ps.add(p);
    EXPECT_EQ(ps.find(7), 0U);
    EXPECT_EQ(ps.find(7, CopyImage{1, 0, 0}), image);
    EXPECT_THROW(ps.add(p), core::Error); // the same (uid, image) twice
    EXPECT_THROW(ps.setImage(image, kNoImage), core::Error);
    ps.setImage(image, CopyImage{0, -1, 0});
    EXPECT_EQ(ps.find(7, CopyImage{0, -1, 0}), image);
    EXPECT_FALSE(ps.contains(7, CopyImage{1, 0, 0}));
    ps.remove(0);
    EXPECT_EQ(ps.find(7, CopyImage{0, -1, 0}), 0U);
    EXPECT_FALSE(ps.contains(7));
}

TEST(ParticleStorage, AReceivedJumpAcrossAWrappedAxisIsANewCopyForTheTrace) {
    ParticleStorage ps;
    ps.setWrapPeriod(regolith::core::Vec3(0.0, 10.0, 0.0)); // y wraps with period 10
    ParticleInit p = grainSeven();
    p.position = regolith::core::Vec3(5.0, 9.9, 5.0);
    p.flags = Flag::Shadow;
    ps.add(p);
    ps.startTracing();
    // A move (even a long one along an axis that does not wrap) is a plain write.
    ps.receivePosition(0, regolith::core::Vec3(7.0, 9.95, 5.0));
    EXPECT_TRUE(ps.traceJournal().empty());
    EXPECT_EQ(ps.traceTag(0), 0U);
    // The master wrapped along y: the copy jumps by a period, a new copy for the follower.
    ps.receivePosition(0, regolith::core::Vec3(7.0, 0.05, 5.0));
    ASSERT_EQ(ps.traceJournal().size(), 1U);
    EXPECT_EQ(ps.traceJournal()[0].index, 0U);
    EXPECT_EQ(ps.traceJournal()[0].previous, 0U);
    EXPECT_EQ(ps.traceTag(0), ParticleStorage::kUntraced);
    EXPECT_TRUE(ps.position(0) == regolith::core::Vec3(7.0, 0.05, 5.0));
}

TEST(ParticleStorage, AShadowSharesItsMastersHistoryUntilTheLayoutChanges) {
    ParticleStorage ps;
    ParticleInit p = grainSeven();
    std::size_t const master = ps.add(p);
    p.uid = 8;
    std::size_t const other = ps.add(p);
    p.uid = 7;
    p.image = CopyImage{1, 0, 0};
    p.flags = Flag::Shadow;
    std::size_t const shadow = ps.add(p);
    ps.history(master).set(HistoryEntry{9, Vec3(0.1, 0.0, 0.0), 3});
    std::array<std::array<std::size_t, 2>, 1> const shared{{{shadow, master}}};
    ps.shareHistories(shared);
    EXPECT_TRUE(ps.sharesHistory(shadow));
    EXPECT_FALSE(ps.sharesHistory(master));
    EXPECT_FALSE(ps.sharesHistory(other));
    EXPECT_EQ(&ps.pairHistory(shadow), &ps.history(master));
    EXPECT_EQ(&ps.pairHistory(other), &ps.history(other));
    // A spring the shadow's pair writes lands in the master's history; the shadow's own
    // history becomes that history again once the layout changes.
    ps.pairHistory(shadow).set(HistoryEntry{11, Vec3(0.0, 0.2, 0.0), 4});
    EXPECT_TRUE(ps.history(shadow).empty());
    ps.remove(other);
    EXPECT_FALSE(ps.sharesHistory(0));
    std::size_t const moved = ps.find(7, CopyImage{1, 0, 0});
    EXPECT_EQ(&ps.pairHistory(moved), &ps.history(moved));
    ASSERT_EQ(ps.history(moved).size(), 2U);
    EXPECT_EQ(ps.history(moved).find(11)->spring, Vec3(0.0, 0.2, 0.0));
    // Only a shadow and its own grain's master may share.
    std::array<std::array<std::size_t, 2>, 1> const wrong{{{master, moved}}};
    EXPECT_THROW(ps.shareHistories(wrong), core::Error);
}

TEST(ParticleStorage, ForgottenSharingLeavesTheShadowsHistoryUntilCopiedFromTheMaster) {
    ParticleStorage ps;
    ParticleInit p = grainSeven();
    std::size_t const master = ps.add(p);
    p.uid = 8; // a shadow whose master lies elsewhere: left alone
    p.flags = Flag::Shadow;
    std::size_t const foreign = ps.add(p);
    p.uid = 7;
    p.image = CopyImage{1, 0, 0};
    std::size_t const shadow = ps.add(p);
    ps.history(foreign).set(HistoryEntry{5, Vec3(0.5, 0.0, 0.0), 1});
    std::array<std::array<std::size_t, 2>, 1> const shared{{{shadow, master}}};
    ps.shareHistories(shared);
    ps.pairHistory(shadow).set(HistoryEntry{11, Vec3(0.0, 0.2, 0.0), 4});
    ps.forgetSharedHistories();
    EXPECT_FALSE(ps.sharesHistory(shadow));
    EXPECT_TRUE(ps.history(shadow).empty()); // not brought up to date
    ps.copyMastersHistoriesToShadows();
    ASSERT_EQ(ps.history(shadow).size(), 1U);
    EXPECT_EQ(ps.history(shadow).find(11)->spring, Vec3(0.0, 0.2, 0.0));
    ASSERT_EQ(ps.history(foreign).size(), 1U);
    EXPECT_EQ(ps.history(foreign).find(5)->spring, Vec3(0.5, 0.0, 0.0));
}

} // namespace
} // namespace regolith::particles
