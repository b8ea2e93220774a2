// SentCache (particles/sync/SentCache.hpp), SOS's per-block sent-cache as a sorted flat
// vector: checked against a std::set model under random inserts, erases, forgets and shifts.
#include "particles/sync/SentCache.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <set>
#include <tuple>
#include <vector>

using namespace regolith::particles;

namespace {

using Key = std::tuple<Uid, std::uint64_t, CopyImage>;

Key keyOf(SentEntry const& e) {
    return {e.uid, e.block, e.image};
}

std::vector<Key> contents(SentCache const& c) {
    std::vector<Key> out;
    for (SentEntry const& e : c.entries())
        out.push_back(keyOf(e));
    return out;
}

} // namespace

TEST(SentCache, InsertIsIdempotentAndOrdered) {
    SentCache c;
    EXPECT_TRUE(c.empty());
    EXPECT_TRUE(c.insert({7, 3, {1, 0, 0}}));
    EXPECT_TRUE(c.insert({2, 9, {0, 0, 0}}));
    EXPECT_TRUE(c.insert({7, 1, {0, 0, -1}}));
    EXPECT_FALSE(c.insert({7, 3, {1, 0, 0}}));
    EXPECT_EQ(c.size(), 3U);
    EXPECT_TRUE(c.contains({7, 1, {0, 0, -1}}));
    EXPECT_FALSE(c.contains({7, 1, {0, 0, 1}}));
    // SentEntry is {block, uid, image}; the cache orders by (uid, block, image).
    std::vector<Key> const expected{{1, 7, {0, 0, -1}}, {3, 7, {1, 0, 0}}, {9, 2, {0, 0, 0}}};
    EXPECT_EQ(contents(c), expected);
}

TEST(SentCache, ForgetRemovesOnlyThatUid) {
    SentCache c;
    for (Uid u = 1; u <= 5; ++u)
        for (std::uint64_t b = 0; b < 3; ++b)
            c.insert({b, u, kNoImage});
    c.forget(3);
    c.forget(42); // absent: no change
    EXPECT_EQ(c.size(), 12U);
    for (SentEntry const& e : c.entries())
        EXPECT_NE(e.uid, 3U);
    EXPECT_TRUE(c.erase({1, 4, kNoImage}));
    EXPECT_FALSE(c.erase({1, 4, kNoImage}));
    EXPECT_EQ(c.size(), 11U);
}

TEST(SentCache, ShiftMovesImagesAndKeepsOrder) {
    SentCache c;
    c.insert({5, 1, {1, 0, 0}});
    c.insert({5, 1, {-1, 0, 0}});
    c.insert({4, 1, {0, 1, 0}});
    c.insert({5, 2, {1, 0, 0}});
    c.shift(1, {1, 0, 0}); // image - delta
    std::vector<Key> const expected{
        {1, 4, {-1, 1, 0}}, {1, 5, {-2, 0, 0}}, {1, 5, {0, 0, 0}}, {2, 5, {1, 0, 0}}};
    EXPECT_EQ(contents(c), expected);
}

TEST(SentCache, MatchesSetModelUnderRandomOperations) {
    std::mt19937 rng(12345);
    std::uniform_int_distribution<int> op(0, 9), uid(1, 20), block(0, 5), im(-2, 2);
    SentCache c;
    std::set<Key> model;
    auto randomEntry = [&] {
        return SentEntry{
            static_cast<std::uint64_t>(block(rng)), static_cast<Uid>(uid(rng)),
            CopyImage{static_cast<std::int8_t>(im(rng)), static_cast<std::int8_t>(im(rng)), 0}};
    };
    for (int step = 0; step < 20000; ++step) {
        int const o = op(rng);
        if (o < 5) {
            SentEntry const e = randomEntry();
            EXPECT_EQ(c.insert(e), model.insert(keyOf(e)).second);
        } else if (o < 7) {
            SentEntry const e = randomEntry();
            EXPECT_EQ(c.erase(e), model.erase(keyOf(e)) == 1);
        } else if (o < 8) {
            auto const u = static_cast<Uid>(uid(rng));
            std::erase_if(model, [&](Key const& k) { return std::get<0>(k) == u; });
            c.forget(u);
        } else if (o < 9) {
            auto const u = static_cast<Uid>(uid(rng));
            CopyImage const d{static_cast<std::int8_t>(im(rng) / 2), 0, 0};
            // Keep images within +-kMaxImage, as the sync does.
            bool ok = true;
            for (Key const& k : model)
                if (std::get<0>(k) == u && std::abs(std::get<2>(k)[0] - d[0]) > 2)
                    ok = false;
            if (!ok)
                continue;
            std::set<Key> next;
            for (Key k : model) {
                if (std::get<0>(k) == u)
                    std::get<2>(k) = subtractImages(std::get<2>(k), d);
                next.insert(k);
            }
            model = std::move(next);
            c.shift(u, d);
        } else {
            SentEntry const e = randomEntry();
            EXPECT_EQ(c.contains(e), model.count(keyOf(e)) == 1);
        }
        ASSERT_EQ(c.size(), model.size());
    }
    EXPECT_EQ(contents(c), std::vector<Key>(model.begin(), model.end()));
}
