// BlockId: bit layout, navigation, ordering, hashing and formatting.
#include "domain/BlockId.hpp"

#include "core/Error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <sstream>
#include <unordered_set>
#include <vector>

using namespace regolith;
using namespace regolith::domain;

namespace {

/// A random id with its root and octant digits, the reference it is compared with.
struct Reference {
    std::uint64_t root;
    std::vector<int> digits;
    BlockId id;
};

Reference randomId(std::mt19937_64& rng) {
    Reference r{std::uniform_int_distribution<std::uint64_t>(0, 40)(rng), {}, {}};
    int const level = std::uniform_int_distribution<int>(0, BlockId::kMaxLevel)(rng);
    r.id = BlockId::root(r.root);
    for (int l = 0; l < level; ++l) {
        r.digits.push_back(std::uniform_int_distribution<int>(0, 7)(rng));
        r.id = r.id.child(r.digits.back());
    }
    return r;
}

} // namespace

TEST(BlockId, RootAndChildrenEncodeLevelRootAndPath) {
    BlockId const root = BlockId::root(12345);
    EXPECT_TRUE(root.isValid());
    EXPECT_EQ(root.level(), 0);
    EXPECT_EQ(root.rootIndex(), 12345U);
    EXPECT_EQ(root.raw(), (std::uint64_t{12345} << BlockId::kPathBits) | 1U);
    for (int k = 0; k < 8; ++k) {
        BlockId const c = root.child(k);
        EXPECT_EQ(c.level(), 1);
        EXPECT_EQ(c.rootIndex(), 12345U);
        EXPECT_EQ(c.octant(), k);
        EXPECT_EQ(c.parent(), root);
        EXPECT_TRUE(root.isAncestorOf(c));
        EXPECT_FALSE(c.isAncestorOf(root));
    }
    BlockId const top = BlockId::root(BlockId::kMaxRootIndex);
    EXPECT_EQ(top.rootIndex(), BlockId::kMaxRootIndex);
    EXPECT_EQ(top.child(7).rootIndex(), BlockId::kMaxRootIndex);
}

TEST(BlockId, RandomPathsRoundTrip) {
    std::mt19937_64 rng(1);
    for (int i = 0; i < 2000; ++i) {
        Reference const r = randomId(rng);
        ASSERT_TRUE(r.id.isValid());
        EXPECT_EQ(r.id.rootIndex(), r.root);
        ASSERT_EQ(r.id.level(), static_cast<int>(r.digits.size()));
        for (int l = 1; l <= r.id.level(); ++l)
            EXPECT_EQ(r.id.octantAt(l), r.digits[static_cast<std::size_t>(l - 1)]);
        BlockId up = r.id;
        while (up.level() > 0) {
            EXPECT_TRUE(up.isAncestorOf(r.id));
            up = up.parent();
        }
        EXPECT_EQ(up, BlockId::root(r.root));
        EXPECT_EQ(BlockId::fromRaw(r.id.raw()), r.id);
    }
}

TEST(BlockId, OrderIsRootThenDepthFirst) {
    std::mt19937_64 rng(2);
    std::vector<Reference> refs;
    for (int i = 0; i < 3000; ++i)
        refs.push_back(randomId(rng));
    refs.push_back({3, {}, BlockId::root(3)}); // an ancestor together with descendants
    refs.push_back({3, {0}, BlockId::root(3).child(0)});
    refs.push_back({3, {0, 0}, BlockId::root(3).child(0).child(0)});
    // Lexicographic order of (root, digits) puts a prefix first: pre-order.
    auto byReference = refs;
    std::sort(byReference.begin(), byReference.end(), [](auto const& a, auto const& b) {
        return std::tie(a.root, a.digits) < std::tie(b.root, b.digits);
    });
    auto byId = refs;
    std::sort(byId.begin(), byId.end(), [](auto const& a, auto const& b) { return a.id < b.id; });
    for (std::size_t i = 0; i < refs.size(); ++i)
        EXPECT_EQ(byId[i].id, byReference[i].id) << i;
    EXPECT_LT(BlockId::root(3).child(7), BlockId::root(4));
    EXPECT_LT(BlockId::root(3).child(1), BlockId::root(3).child(1).child(0));
    EXPECT_LT(BlockId::root(3).child(0).child(7), BlockId::root(3).child(1));
}

TEST(BlockId, HashSeparatesDistinctIds) {
    std::mt19937_64 rng(3);
    std::unordered_set<BlockId> ids;
    std::unordered_set<std::uint64_t> raws;
    for (int i = 0; i < 5000; ++i) {
        BlockId const id = randomId(rng).id;
        ids.insert(id);
        raws.insert(id.raw());
    }
    EXPECT_EQ(ids.size(), raws.size());
    // Siblings differ in the lowest bits only; their hashes must still differ.
    std::unordered_set<std::size_t> hashes;
    for (int k = 0; k < 8; ++k)
        hashes.insert(std::hash<BlockId>{}(BlockId::root(9).child(k)));
    EXPECT_EQ(hashes.size(), 8U);
}

TEST(BlockId, FormatsRootAndPath) {
    EXPECT_EQ(BlockId::root(12).toString(), "12");
    BlockId const id = BlockId::root(12).child(0).child(7).child(3);
    EXPECT_EQ(id.toString(), "12.0.7.3");
    std::ostringstream os;
    os << id;
    EXPECT_EQ(os.str(), "12.0.7.3");
}

TEST(BlockId, MisuseThrowsAndInvalidIdsAreDetected) {
    EXPECT_THROW((void)BlockId::root(BlockId::kMaxRootIndex + 1), core::Error);
    EXPECT_THROW((void)BlockId::root(0).parent(), core::Error);
    EXPECT_THROW((void)BlockId::root(0).child(8), core::Error);
    EXPECT_THROW((void)BlockId::root(0).child(-1), core::Error);
    BlockId deep = BlockId::root(0);
    for (int l = 0; l < BlockId::kMaxLevel; ++l)
        deep = deep.child(l % 8);
    EXPECT_EQ(deep.level(), BlockId::kMaxLevel);
    EXPECT_THROW((void)deep.child(0), core::Error);
    EXPECT_FALSE(BlockId{}.isValid());
    EXPECT_FALSE(BlockId::fromRaw(0b10).isValid()); // marker not at a multiple of 3 bits
    EXPECT_TRUE(BlockId::fromRaw(0b1000).isValid());
}
