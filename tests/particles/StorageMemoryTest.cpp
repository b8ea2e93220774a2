// The storage's memory layout (docs/notes/memory.md): owners as slots in a table of the
// distinct owners, contact histories as one pointer that exists only with entries, exact
// reservation followed by gentle growth. Each test fails if the compact form loses data or
// if the layout falls back to the larger one.
#include "core/memory/GentleGrowth.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <vector>

namespace {

using namespace regolith::particles;
using regolith::core::Vec3;

ParticleInit grain(Uid uid, BlockRef owner) {
    ParticleInit p;
    p.uid = uid;
    p.position = Vec3(static_cast<double>(uid), 0.0, 0.0);
    p.radius = 0.5;
    p.mass = 1.0;
    p.owner = owner;
    return p;
}

TEST(StorageMemory, OwnersSurviveAddRemovePermuteAndSetOwner) {
    // Owners from a handful of blocks on a few ranks, changed, removed and permuted at random;
    // a map from uid to owner is the model.
    ParticleStorage ps;
    std::map<Uid, BlockRef> model;
    std::mt19937_64 rng(11);
    auto randomOwner = [&] { return BlockRef{static_cast<int>(rng() % 3), 100 + rng() % 5}; };
    for (Uid u = 1; u <= 400; ++u) {
        BlockRef const o = randomOwner();
        ps.add(grain(u, o));
        model[u] = o;
    }
    for (int op = 0; op < 2000; ++op) {
        Uid const u = 1 + rng() % 400;
        auto const i = ps.find(u);
        if (i == ParticleStorage::kNotFound)
            continue;
        if (rng() % 4 == 0) {
            ps.remove(i);
            model.erase(u);
        } else {
            BlockRef const o = randomOwner();
            ps.setOwner(i, o);
            model[u] = o;
        }
    }
    std::vector<std::size_t> reversed(ps.size());
    for (std::size_t k = 0; k < reversed.size(); ++k)
        reversed[k] = reversed.size() - 1 - k;
    ps.permute(reversed);
    ASSERT_EQ(ps.size(), model.size());
    for (auto const& [uid, owner] : model) {
        auto const i = ps.find(uid);
        ASSERT_NE(i, ParticleStorage::kNotFound) << uid;
        EXPECT_EQ(ps.owner(i), owner) << uid;
    }
}

TEST(StorageMemory, EmptyHistoriesHoldNoHeapAndCopiesAreDeep) {
    static_assert(sizeof(ContactHistory) == sizeof(void*), "one pointer per copy");
    ContactHistory a;
    EXPECT_EQ(a.heapBytes(), 0U);
    EXPECT_TRUE(a.entries().empty());
    EXPECT_EQ(a.find(3), nullptr);
    EXPECT_FALSE(a.erase(3));
    EXPECT_EQ(a.keepOnly(1), 0U);
    a.touch(3, 1).spring = Vec3(1, 2, 3);
    ContactHistory b = a; // a copy owns its own entries
    b.touch(3, 1).spring = Vec3(0, 0, 0);
    EXPECT_EQ(a.find(3)->spring, Vec3(1, 2, 3));
    ContactHistory c = std::move(a);
    EXPECT_EQ(c.find(3)->spring, Vec3(1, 2, 3));
    EXPECT_TRUE(c.erase(3)); // the last entry gone: the heap block too
    EXPECT_TRUE(c.empty());
    EXPECT_EQ(c.heapBytes(), 0U);
}

TEST(StorageMemory, HolderListsAreOnePointerAndBehaveLikeSortedVectors) {
    static_assert(sizeof(HolderList) == sizeof(void*), "one pointer per copy");
    HolderList h;
    EXPECT_TRUE(h.empty());
    EXPECT_EQ(h.begin(), h.end());
    EXPECT_EQ(h.heapBytes(), 0U);
    // Sorted inserts as the synchronisation does them (lower_bound + insert).
    for (int r : {3, 1, 2, 1}) {
        CopyRef const t{r, 7, kNoImage};
        auto* at = std::lower_bound(h.begin(), h.end(), t);
        if (at == h.end() || !(*at == t))
            h.insert(at, t);
    }
    ASSERT_EQ(h.size(), 3U);
    EXPECT_EQ(h.at(0).rank, 1);
    EXPECT_EQ(h.back().rank, 3);
    HolderList copy = h; // deep
    h.erase(std::remove(h.begin(), h.end(), CopyRef{2, 7, kNoImage}), h.end());
    EXPECT_EQ(h.size(), 2U);
    EXPECT_EQ(copy.size(), 3U);
    h.erase(h.begin(), h.end()); // the last ones gone: the heap block too
    EXPECT_TRUE(h.empty());
    EXPECT_EQ(h.heapBytes(), 0U);
    h = std::vector<CopyRef>{{5, 1, kNoImage}};
    EXPECT_EQ(h.vector(), (std::vector<CopyRef>{{5, 1, kNoImage}}));
    h.pop_back();
    EXPECT_TRUE(h.empty());
    EXPECT_TRUE(h.vector().empty());
}

TEST(StorageMemory, HolderListsAgreeWithAVectorUnderRandomEdits) {
    std::mt19937 rng(7);
    HolderList h;
    std::vector<CopyRef> model;
    for (int op = 0; op < 4000; ++op) {
        CopyRef const t{static_cast<int>(rng() % 9), rng() % 3, kNoImage};
        switch (rng() % 6) {
        case 0: // sorted insert
        case 1: {
            auto const at = static_cast<std::size_t>(
                std::lower_bound(model.begin(), model.end(), t) - model.begin());
            model.insert(model.begin() + static_cast<std::ptrdiff_t>(at), t);
            h.insert(h.begin() + at, t);
            break;
        }
        case 2: // erase a range
            if (!model.empty()) {
                std::size_t const a = rng() % model.size();
                std::size_t const b = a + rng() % (model.size() - a + 1);
                model.erase(model.begin() + static_cast<std::ptrdiff_t>(a),
                            model.begin() + static_cast<std::ptrdiff_t>(b));
                h.erase(h.begin() + a, h.begin() + b);
            }
            break;
        case 3: // push and pop
            model.push_back(t);
            h.push_back(t);
            if (rng() % 2 == 0) {
                model.pop_back();
                h.pop_back();
            }
            break;
        case 4: { // assign (shorter or longer), copy and move
            std::vector<CopyRef> const v(
                model.begin(),
                model.begin() + static_cast<std::ptrdiff_t>(rng() % (model.size() + 1)));
            model = v;
            HolderList other;
            other = v;
            HolderList copied = other;
            h = std::move(copied);
            break;
        }
        default:
            if (rng() % 20 == 0) {
                model.clear();
                h.clear();
            }
        }
        ASSERT_EQ(h.vector(), model) << "after operation " << op;
        ASSERT_EQ(h.empty(), model.empty());
        ASSERT_EQ(h.heapBytes() == 0, model.empty()) << "an empty list holds no block";
    }
}

TEST(StorageMemory, ReservedStorageGrowsGentlyNotByDoubling) {
    // A storage reserved for its masters (the set-up) that then gets its first shadow must
    // not double: it grows by gentleCapacity, about 1/16.
    std::size_t const n = 4096;
    ParticleStorage ps;
    ps.reserve(n);
    for (Uid u = 1; u <= n; ++u)
        ps.add(grain(u, BlockRef{0, 1}));
    std::size_t const full = ps.bytes();
    ParticleInit shadow = grain(n + 1, BlockRef{1, 2});
    shadow.flags = Flags(Flag::Shadow);
    ps.add(shadow);
    double const growth = static_cast<double>(ps.bytes()) / static_cast<double>(full);
    // The copy index may double (a power-of-two table) but the arrays may not.
    EXPECT_LT(growth, 1.0 + 1.0 / 16.0 + 0.25) << full << " -> " << ps.bytes();
    EXPECT_EQ(regolith::core::gentleCapacity(1600), 1600U + 100U + 16U);
    std::vector<int> v(100);
    v.shrink_to_fit();
    regolith::core::reserveForAppend(v);
    EXPECT_EQ(v.capacity(), regolith::core::gentleCapacity(100));
}

} // namespace
