// A grain's contact history: entries sorted by partner, touched with hints, pruned by stamp.
#include "particles/storage/ContactHistory.hpp"

#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;

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

TEST(ContactHistory, AnEntryNotTouchedInThePreviousPassStartsFromAZeroSpring) {
    // The masters' histories are pruned only every few passes, so an entry of a contact that
    // broke may still be there when the pair touches again: it must start afresh, as the new
    // entry of a pruned history would, by search and through a hint alike.
    ContactHistory h;
    std::uint8_t hint = 0;
    h.touch(7, 1, hint).spring = Vec3(1, 2, 3);
    h.touch(9, 1).spring = Vec3(4, 5, 6);
    EXPECT_EQ(h.touch(7, 2, hint).spring, Vec3(1, 2, 3)); // touched in pass 1: kept
    EXPECT_EQ(h.touch(9, 3).spring, Vec3::Zero());        // not in pass 2: broke
    EXPECT_EQ(h.touch(7, 4, hint).spring, Vec3::Zero());  // not in pass 3: broke
    h.touch(7, 4, hint).spring = Vec3(0, 1, 0);
    bool again = false;
    EXPECT_EQ(h.touch(7, 4, hint, again).spring, Vec3(0, 1, 0)); // the same pass again: kept
    EXPECT_TRUE(again);
    EXPECT_EQ(h.size(), 2U); // nothing dropped: that is keepOnly's job
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
