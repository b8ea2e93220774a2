// Particle storage: uids, flags, contact history and the SoA container with its uid map.
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

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

TEST(ContactHistory, SortedByPartnerAndPrunedByStamp) {
    ContactHistory h;
    h.touch(30, 1).spring = Vec3(1, 0, 0);
    h.touch(10, 1).spring = Vec3(2, 0, 0);
    h.touch(20, 1);
    ASSERT_EQ(h.size(), 3U);
    std::vector<Uid> order;
    for (auto const& e : h)
        order.push_back(e.partner);
    EXPECT_EQ(order, (std::vector<Uid>{10, 20, 30}));
    EXPECT_EQ(h.find(10)->spring.x(), 2.0);
    EXPECT_EQ(h.find(15), nullptr);
    // Next pass: 10 and 30 touched again (30 keeps its spring), 20 broke.
    EXPECT_EQ(h.touch(30, 2).spring.x(), 1.0);
    h.touch(10, 2);
    EXPECT_EQ(h.keepOnly(2), 1U);
    EXPECT_EQ(h.find(20), nullptr);
    EXPECT_TRUE(h.erase(10));
    EXPECT_FALSE(h.erase(10));
    h.set(HistoryEntry{5, Vec3(0, 3, 0), 2});
    EXPECT_EQ(h.entries().front().partner, 5U);
    EXPECT_EQ(h.keepOnly(3), 2U);
    EXPECT_TRUE(h.empty());
    EXPECT_EQ(h.heapBytes(), 0U);
}

TEST(ContactHistory, TouchWithAHintFindsTheEntryWhereverTheHintPoints) {
    ContactHistory h;
    std::uint8_t hint20 = 0, hint30 = 7; // 7: beyond the end, a miss
    h.touch(30, 1, hint30).spring = Vec3(3, 0, 0);
    EXPECT_EQ(hint30, 0U);
    h.touch(20, 1, hint20).spring = Vec3(2, 0, 0); // inserted before 30: hint30 is now stale
    EXPECT_EQ(hint20, 0U);
    EXPECT_EQ(h.touch(30, 2, hint30).spring.x(), 3.0); // stale hint: searched, and refreshed
    EXPECT_EQ(hint30, 1U);
    EXPECT_EQ(h.touch(30, 2, hint30).spring.x(), 3.0); // hit
    EXPECT_EQ(h.find(30)->stamp, 2U);
    EXPECT_EQ(h.touch(20, 2, hint20).spring.x(), 2.0);
    EXPECT_EQ(h.size(), 2U);
    EXPECT_EQ(h.keepOnly(2), 0U);
}

TEST(ContactHistory, AgreesWithAnOrderedMapUnderRandomEdits) {
    // Inserts in the middle, growth of the block, removals down to empty (block freed),
    // assign into a smaller and a larger block, copies and moves: the entries must always be
    // those of a std::map keyed by partner, in its order.
    std::mt19937_64 rng(11);
    ContactHistory h;
    std::map<Uid, HistoryEntry> model;
    auto same = [&](ContactHistory const& x) {
        ASSERT_EQ(x.size(), model.size());
        ASSERT_EQ(x.empty(), model.empty());
        EXPECT_EQ(x.heapBytes() == 0, model.empty());
        auto it = model.begin();
        for (HistoryEntry const& e : x) {
            EXPECT_EQ(e.partner, it->first);
            EXPECT_EQ(e.stamp, it->second.stamp);
            EXPECT_EQ(e.spring, it->second.spring);
            ++it;
        }
    };
    for (std::uint32_t step = 1; step <= 3000; ++step) {
        Uid const partner = rng() % 40;
        switch (rng() % 6) {
        case 0:
        case 1: { // touch, and write a spring
            std::uint8_t hint = static_cast<std::uint8_t>(rng() % 8);
            HistoryEntry& e = h.touch(partner, step, hint);
            e.spring = Vec3(double(step), double(partner), 1.0);
            ASSERT_EQ(h.entries()[hint].partner, partner);
            model[partner] = HistoryEntry{partner, e.spring, step};
            break;
        }
        case 2:
            h.set(HistoryEntry{partner, Vec3(-1.0, double(step), 0.0), step});
            model[partner] = HistoryEntry{partner, Vec3(-1.0, double(step), 0.0), step};
            break;
        case 3:
            EXPECT_EQ(h.erase(partner), model.erase(partner) == 1);
            break;
        case 4: { // keep the entries stamped in the last few steps
            std::uint32_t const keep = step - 1;
            std::size_t dropped = 0;
            for (auto it = model.begin(); it != model.end();)
                if (it->second.stamp != keep) {
                    it = model.erase(it);
                    ++dropped;
                } else {
                    ++it;
                }
            EXPECT_EQ(h.keepOnly(keep), dropped);
            break;
        }
        default: { // through a copy, a move and an assign from another history's entries
            ContactHistory copy(h);
            ContactHistory moved(std::move(copy));
            ContactHistory other;
            other.touch(1000, 1);
            other.touch(1001, 1);
            other.touch(1002, 1);
            other.assign(moved.entries());
            h = other;
            break;
        }
        }
        same(h);
    }
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
    EXPECT_EQ(walls[k].normal, Vec3::UnitZ());
    EXPECT_EQ(walls[k].uid, wallUid(0));
    EXPECT_DOUBLE_EQ(walls[k].distance(Vec3(5, 5, 3)), 2.0);
    EXPECT_THROW(walls.add(Vec3::Zero(), Vec3::Zero()), InputError);
    EXPECT_THROW(walls.add(Vec3::Zero(), Vec3(std::nan(""), 0, 1)), InputError);
    EXPECT_EQ(walls.size(), 1U);
}

namespace regolith::particles {
namespace {

TEST(ParticleStorage, OneUidAtSeveralPeriodicImages) {
    ParticleStorage ps;
    ParticleInit p;
    p.uid = 7;
    p.radius = 0.5;
    p.mass = 1.0;
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

} // namespace
} // namespace regolith::particles

TEST(CopyIndex, AgreesWithAnOrderedMapUnderRandomInsertsAndErases) {
    // Backward-shift deletion must keep every remaining key reachable, also across the wrap
    // of the slot array and through growth. The index keeps no keys: like ParticleStorage,
    // the test keeps them in an array (`keys`) whose positions are the stored values.
    regolith::particles::CopyIndex index;
    std::vector<CopyKey> keys;
    auto const keyAt = [&keys](std::uint32_t i) { return keys.at(i); };
    std::map<CopyKey, std::uint32_t> reference;
    std::mt19937_64 rng(3);
    for (int op = 0; op < 20000; ++op) {
        CopyKey const key{rng() % 600, CopyImage{static_cast<std::int8_t>(rng() % 3), 0, 0}};
        if (rng() % 3 == 0) {
            index.erase(key, keyAt);
            reference.erase(key);
        } else {
            auto const value = static_cast<std::uint32_t>(keys.size());
            keys.push_back(key);
            EXPECT_EQ(index.insert(key, value, keyAt), reference.emplace(key, value).second);
        }
        if (op % 97 == 0) {
            for (auto const& [k, v] : reference)
                ASSERT_EQ(index.find(k, keyAt), v) << "op " << op;
            ASSERT_EQ(index.size(), reference.size());
        }
    }
    EXPECT_EQ(index.find(CopyKey{100000, kNoImage}, keyAt), regolith::particles::CopyIndex::kNone);
}

TEST(CopyIndex, EightBytesPerSlotAndAssignRepoints) {
    regolith::particles::CopyIndex index;
    std::vector<CopyKey> keys{{7, kNoImage}, {7, CopyImage{1, 0, 0}}, {9, kNoImage}};
    auto const keyAt = [&keys](std::uint32_t i) { return keys.at(i); };
    for (std::uint32_t i = 0; i < keys.size(); ++i)
        ASSERT_TRUE(index.insert(keys[i], i, keyAt));
    EXPECT_FALSE(index.insert(CopyKey{7, kNoImage}, 2, keyAt)); // present
    EXPECT_EQ(index.bytes(), 16U * 8U); // the smallest table: 16 slots of 8 bytes
    // Move key 2 to position 0 the way ParticleStorage::remove does: copy, assign, drop.
    index.erase(keys[0], keyAt);
    keys[0] = keys[2];
    index.assign(keys[0], 0, keyAt);
    keys.pop_back();
    EXPECT_EQ(index.find(CopyKey{9, kNoImage}, keyAt), 0U);
    EXPECT_EQ(index.find(CopyKey{7, CopyImage{1, 0, 0}}, keyAt), 1U);
    EXPECT_EQ(index.find(CopyKey{7, kNoImage}, keyAt), regolith::particles::CopyIndex::kNone);
    EXPECT_EQ(index.size(), 2U);

    // Sized to the keys, not to a power of two: 100,000 keys at most 3/4 full with a
    // sixteenth of headroom take ~11.3 bytes each (2^18 slots would be 21).
    regolith::particles::CopyIndex big;
    big.reserve(100000);
    EXPECT_GE(big.bytes(), 8U * 100000U * 4U / 3U);
    EXPECT_LT(big.bytes(), 12U * 100000U);
}
