// The (uid, image) -> index table of ParticleStorage: open addressing, backward-shift deletion,
// sized to its keys.
#include "particles/storage/CopyIndex.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

using namespace regolith::particles;

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
