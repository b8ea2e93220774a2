// The update policy: recompute only after a grain moved more than the threshold (global
// over ranks), count updates, warn when the threshold exceeds the grain spacing, and a lazy
// threshold gives a visibly worse field than a careful one.
#include "gravity/update/UpdatePolicy.hpp"

#include "core/Error.hpp"
#include "gravity/tree/BarnesHut.hpp"
#include "tests/gravity/GravityTestUtil.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

using namespace regolith;
using namespace regolith::testing;

TEST(UpdatePolicy, TriggersOnTheLargestDisplacementOfAnyRank) {
    gravity::UpdatePolicy policy(1.0);
    std::vector<std::uint64_t> uid{static_cast<std::uint64_t>(world().rank())};
    std::vector<double> x{0.0}, y{0.0}, z{0.0};
    EXPECT_TRUE(policy.due(world(), uid, x, y, z)); // never updated
    policy.markUpdated(uid, x, y, z);
    x[0] = 0.5;
    EXPECT_FALSE(policy.due(world(), uid, x, y, z));
    // Only the last rank's grain moves past the threshold: every rank must agree.
    if (world().rank() == world().size() - 1)
        x[0] = 1.5;
    EXPECT_TRUE(policy.due(world(), uid, x, y, z));
    EXPECT_DOUBLE_EQ(policy.lastMaxDisplacement(), 1.5);
    policy.markUpdated(uid, x, y, z);
    EXPECT_EQ(policy.updates(), 2);
    // A grain this rank did not hold at the update counts as moved.
    uid[0] += 1000;
    EXPECT_TRUE(policy.due(world(), uid, x, y, z));
}

TEST(UpdatePolicy, AWrapAcrossAPeriodicFaceIsOnlyTheStep) {
    // A grain 0.1 inside the lower x face of a periodic domain of extent 10 steps 0.2 across
    // it and is wrapped to 9.9: it moved 0.2, not 9.8 (which would count an update at every
    // crossing). The open axis y counts the whole displacement.
    std::vector<std::uint64_t> uid{static_cast<std::uint64_t>(world().rank())};
    std::vector<double> x{0.1}, y{5.0}, z{5.0};
    gravity::UpdatePolicy periodic(0.5, {10.0, 0.0, 10.0});
    gravity::UpdatePolicy open(0.5);
    for (gravity::UpdatePolicy* p : {&periodic, &open})
        p->markUpdated(uid, x, y, z);
    x[0] = 9.9;
    EXPECT_FALSE(periodic.due(world(), uid, x, y, z));
    EXPECT_NEAR(periodic.lastMaxDisplacement(), 0.2, 1e-12);
    EXPECT_TRUE(open.due(world(), uid, x, y, z));
    y[0] = 5.6; // beyond the threshold on the open axis
    EXPECT_TRUE(periodic.due(world(), uid, x, y, z));
}

TEST(UpdatePolicy, GrainsThatChangeRankBringTheirRecord) {
    // Layout independence: a grain that moved to another rank (here every grain moves to the
    // next rank) keeps its reference and field, so no update is forced; its displacement
    // still counts.
    int const p = world().size();
    int const r = world().rank();
    gravity::UpdatePolicy policy(1.0);
    std::vector<std::uint64_t> uid{static_cast<std::uint64_t>(100 + r)};
    std::vector<double> x{static_cast<double>(r)}, y{0.0}, z{0.0};
    std::vector<double> ax{0.5 * r}, ay{-1.0}, az{2.0};
    EXPECT_TRUE(policy.due(world(), uid, x, y, z));
    policy.markUpdated(uid, x, y, z, ax, ay, az);
    int const from = (r + p - 1) % p; // this rank now holds the grain of rank `from`
    uid[0] = static_cast<std::uint64_t>(100 + from);
    x[0] = from + 0.25;
    EXPECT_FALSE(policy.due(world(), uid, x, y, z));
    EXPECT_DOUBLE_EQ(policy.lastMaxDisplacement(), 0.25);
    gravity::GrainRecord const* record = policy.record(uid[0]);
    ASSERT_NE(record, nullptr);
    EXPECT_EQ(record->field[0], 0.5 * from);
    EXPECT_EQ(record->reference[0], static_cast<double>(from));
    if (p > 1) {
        EXPECT_EQ(policy.record(static_cast<std::uint64_t>(100 + r)), nullptr); // given away
    }
    // Moved on again, now past the threshold: due everywhere.
    uid[0] = static_cast<std::uint64_t>(100 + (from + p - 1) % p);
    x[0] = (from + p - 1) % p + 1.5;
    EXPECT_TRUE(policy.due(world(), uid, x, y, z));
    EXPECT_EQ(policy.updates(), 1);
}

TEST(UpdatePolicy, ARankLeftWithoutGrainsGivesItsRecordsAway) {
    // With an update interval: after an update rank 0's grain moves to rank 1, and rank 0 is
    // left with none (a rebalance that leaves a rank only empty blocks). Its record reaches the
    // grain's new rank, and the emptied rank holds no pointer into the records the update replaced
    // (the address sanitizer build checks).
    int const p = world().size();
    int const r = world().rank();
    gravity::UpdatePolicy policy(0.0, {0.0, 0.0, 0.0}, {4, false, 0.0, 0.1});
    std::vector<std::uint64_t> uid{static_cast<std::uint64_t>(100 + r)};
    std::vector<double> x{static_cast<double>(r)}, y{0.0}, z{0.0};
    std::vector<double> ax{0.5 * r + 1.0}, ay{0.0}, az{0.0};
    EXPECT_TRUE(policy.due(world(), uid, x, y, z));
    policy.markUpdated(uid, x, y, z, ax, ay, az);
    EXPECT_FALSE(policy.due(world(), uid, x, y, z)); // finds each grain's record ...
    policy.markUpdated(uid, x, y, z, ax, ay, az);    // ... which the next update replaces
    std::vector<std::uint64_t> now;
    if (r == 1 || p == 1) // rank 0's grain, on rank 1
        now.push_back(100);
    if (r > 0)
        now.push_back(static_cast<std::uint64_t>(100 + r));
    std::vector<double> const at(now.size(), 0.0);
    for (int k = 0; k < 2; ++k)
        EXPECT_FALSE(policy.due(world(), now, at, at, at));
    for (std::uint64_t const u : now) {
        gravity::GrainRecord const* record = policy.record(u);
        ASSERT_NE(record, nullptr) << "grain " << u;
        EXPECT_EQ(record->field[0], 0.5 * static_cast<double>(u - 100) + 1.0);
    }
}

TEST(UpdatePolicy, RestoredRecordsReachTheirGrainsOnAnyRank) {
    // A checkpoint's records arrive wherever the file slice was read (here all on the last
    // rank); the first due() brings each to its grain. A NaN record counts as none.
    int const p = world().size();
    int const r = world().rank();
    double const nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<std::uint64_t> uids;
    std::vector<gravity::GrainRecord> records;
    if (r == p - 1)
        for (int k = 0; k < p; ++k) {
            uids.push_back(static_cast<std::uint64_t>(7 * k + 1));
            records.push_back({{1.0 * k, 0.0, 0.0}, {3.0 * k, 0.0, 0.0}});
        }
    gravity::UpdatePolicy policy(0.5);
    policy.restore(4, uids, records);
    EXPECT_EQ(policy.updates(), 4);
    std::vector<std::uint64_t> uid{static_cast<std::uint64_t>(7 * r + 1)};
    std::vector<double> x{r + 0.125}, y{0.0}, z{0.0};
    EXPECT_FALSE(policy.due(world(), uid, x, y, z));
    ASSERT_NE(policy.record(uid[0]), nullptr);
    EXPECT_EQ(policy.record(uid[0])->field[0], 3.0 * r);

    gravity::UpdatePolicy fresh(0.5);
    std::vector<gravity::GrainRecord> const none{{{nan, nan, nan}, {nan, nan, nan}}};
    std::vector<std::uint64_t> const one{uid[0]};
    fresh.restore(4, one, none);
    EXPECT_TRUE(fresh.due(world(), uid, x, y, z)); // no record anywhere: update
}

TEST(UpdatePolicy, WarnsWhenTheThresholdExceedsTheSpacing) {
    EXPECT_TRUE(gravity::UpdatePolicy::thresholdWarning(50.0, 80.0).empty());
    std::string const w = gravity::UpdatePolicy::thresholdWarning(160.0, 80.0);
    EXPECT_NE(w.find("gravity.update_threshold"), std::string::npos) << w;
    EXPECT_NE(w.find("400%"), std::string::npos) << w;
    EXPECT_THROW(gravity::UpdatePolicy(-1.0), core::InputError);
}

TEST(UpdatePolicy, LazyThresholdGivesLargeErrors) {
    // Grains drifting at up to 1 m/s for 40 s; the field is refreshed by the tree when the
    // policy says so, then compared with the exact field at the final positions.
    auto const body = testAgglomerate(2000, 17);
    auto const run = [&](double threshold, long long& updates) {
        auto local = localSlab(world(), body);
        std::vector<std::uint64_t> uid(local.size());
        std::mt19937_64 rng(99 + static_cast<std::uint64_t>(world().rank()));
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        std::vector<double> vx(local.size()), vy(local.size()), vz(local.size());
        for (std::size_t i = 0; i < local.size(); ++i) {
            uid[i] = i;
            vx[i] = u(rng);
            vy[i] = u(rng);
            vz[i] = u(rng);
        }
        gravity::UpdatePolicy policy(threshold);
        gravity::tree::BarnesHut tree(world(), {});
        Field f(local.size());
        for (int step = 0; step <= 40; ++step) {
            if (step > 0)
                for (std::size_t i = 0; i < local.size(); ++i) {
                    local.x[i] += vx[i];
                    local.y[i] += vy[i];
                    local.z[i] += vz[i];
                }
            if (policy.due(world(), uid, local.x, local.y, local.z)) {
                tree.evaluate(local.view(), f.out());
                policy.markUpdated(uid, local.x, local.y, local.z);
            }
        }
        updates = policy.updates();
        // The exact field at the final positions of all grains.
        gravity::samples::Body moved;
        for (int r = 0; r < world().size(); ++r) {
            // every rank rebuilds every slab's final positions from the same recipe
            auto slab = gravity::samples::slabOf(body, r, world().size());
            std::mt19937_64 g(99 + static_cast<std::uint64_t>(r));
            for (std::size_t i = 0; i < slab.size(); ++i) {
                double const v[3] = {u(g), u(g), u(g)};
                for (int step = 0; step < 40; ++step) { // the same sums as above, bit for bit
                    slab.x[i] += v[0];
                    slab.y[i] += v[1];
                    slab.z[i] += v[2];
                }
                moved.push(slab, i);
            }
        }
        Field const ref = referenceField(local, moved, gravity::kNewtonG);
        return gravity::errorStats(world(), gravity::relativeErrors(f.view(), ref.view()));
    };
    double const spacing = 80.0; // mean grain diameter ~80 m, packing 0.3
    long long lazyUpdates = 0;
    long long goodUpdates = 0;
    auto const lazy = run(200.0, lazyUpdates);
    auto const good = run(2.0, goodUpdates);
    if (world().rank() == 0)
        std::printf("threshold 200 m: %lld updates, median error %.3e; threshold 2 m: %lld "
                    "updates, median error %.3e\n",
                    lazyUpdates, lazy.median, goodUpdates, good.median);
    EXPECT_FALSE(gravity::UpdatePolicy::thresholdWarning(200.0, spacing).empty());
    EXPECT_EQ(lazyUpdates, 1);
    EXPECT_GT(goodUpdates, 10);
    EXPECT_GT(lazy.median, 10.0 * good.median);
    EXPECT_GT(lazy.median, 1e-2);
}
