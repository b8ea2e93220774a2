// The update policy by the step count (gravity.update_every, UpdateInterval): due every n
// steps, the field extrapolated linearly in time from the last two updates (exact for a field
// that changes linearly), a grain that changed rank bringing its slope along, and an adaptive
// interval that grows while the prediction error is below its budget and shrinks above it.
#include "core/Error.hpp"
#include "gravity/update/UpdatePolicy.hpp"
#include "tests/gravity/GravityTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace regolith;
using namespace regolith::testing;

namespace {

/// One grain per rank, whose field at time t is f0 + rate t (uid = rank).
struct LinearField {
    double f0 = 2.0, rate = 0.5, dt = 0.1;
    std::vector<std::uint64_t> uid{static_cast<std::uint64_t>(world().rank())};
    std::vector<double> x{0.0}, y{0.0}, z{0.0};
    std::vector<double> ax{0.0}, ay{0.0}, az{0.0};
    void at(long long step) { ax[0] = f0 + rate * dt * static_cast<double>(step); }
};

} // namespace

TEST(UpdateInterval, DueEveryNStepsWithTheFieldExtrapolated) {
    LinearField f;
    gravity::UpdatePolicy policy(0.0, {0.0, 0.0, 0.0}, {3, false, 0.0, f.dt});
    for (long long step = 0; step <= 9; ++step) {
        bool const due = policy.due(world(), f.uid, f.x, f.y, f.z);
        EXPECT_EQ(due, step % 3 == 0) << step;
        f.at(step);
        if (due) {
            policy.markUpdated(f.uid, f.x, f.y, f.z, f.ax, f.ay, f.az);
            continue;
        }
        auto const a = policy.fieldAt(0);
        // The first interval keeps the field; from the second update on the slope is known.
        double const expected = step < 3 ? f.f0 : f.ax[0];
        EXPECT_NEAR(a[0], expected, 1e-12) << step;
    }
    EXPECT_EQ(policy.updates(), 4);
}

TEST(UpdateInterval, AllFieldsAtOnceAreEachGrainsField) {
    // Three grains with different fields and slopes in every component: the one-pass
    // extrapolation gives each grain's fieldAt() bit for bit, in the order given to due().
    double const dt = 0.1;
    std::vector<std::uint64_t> uid{7, 3, 11};
    std::vector<double> const x(3, 0.0);
    gravity::UpdatePolicy policy(0.0, {0.0, 0.0, 0.0}, {2, false, 0.0, dt});
    auto field = [](int update, std::size_t i, int a) {
        double const g = static_cast<double>(i);
        return 1.0 + 0.3 * g - 0.7 * a + 0.11 * update * (a + 1.0 + g);
    };
    std::vector<double> fx(3), fy(3), fz(3);
    int update = 0;
    for (long long step = 0; step <= 5; ++step) {
        if (policy.due(world(), uid, x, x, x)) {
            std::vector<double> ax(3), ay(3), az(3);
            for (std::size_t i = 0; i < 3; ++i) {
                ax[i] = field(update, i, 0);
                ay[i] = field(update, i, 1);
                az[i] = field(update, i, 2);
            }
            policy.markUpdated(uid, x, x, x, ax, ay, az);
            ++update;
            continue;
        }
        policy.fieldsAt(fx, fy, fz);
        for (std::size_t i = 0; i < 3; ++i) {
            auto const one = policy.fieldAt(i);
            EXPECT_EQ(fx[i], one[0]) << step << " " << i;
            EXPECT_EQ(fy[i], one[1]) << step << " " << i;
            EXPECT_EQ(fz[i], one[2]) << step << " " << i;
        }
        if (step == 5) { // after two updates: extrapolated, not the kept field
            EXPECT_NE(fx[1], field(update - 1, 1, 0));
        }
    }
}

TEST(UpdateInterval, AGrainThatChangesRankBringsItsSlope) {
    int const p = world().size();
    LinearField f;
    gravity::UpdatePolicy policy(0.0, {0.0, 0.0, 0.0}, {4, false, 0.0, f.dt});
    for (long long step = 0; step <= 4; step += 4) {
        ASSERT_TRUE(policy.due(world(), f.uid, f.x, f.y, f.z));
        f.at(step);
        policy.markUpdated(f.uid, f.x, f.y, f.z, f.ax, f.ay, f.az);
        for (int k = 1; k < 4 && step == 0; ++k)
            ASSERT_FALSE(policy.due(world(), f.uid, f.x, f.y, f.z));
    }
    // Every grain moves to the next rank: not due, and the field goes on along its line.
    f.uid[0] = static_cast<std::uint64_t>((world().rank() + p - 1) % p);
    EXPECT_FALSE(policy.due(world(), f.uid, f.x, f.y, f.z));
    gravity::GrainRecord const* r = policy.record(f.uid[0]);
    ASSERT_NE(r, nullptr);
    EXPECT_NEAR(policy.fieldAt(0)[0], f.f0 + f.rate * f.dt * 5.0, 1e-12);
}

TEST(UpdateInterval, AdaptsToThePredictionError) {
    // A field that changes linearly is predicted exactly once the slopes are known: the
    // interval doubles at every update up to its maximum. One that jumps at every update
    // misses by far more than the budget: the interval halves down to one step.
    double const dt = 0.01;
    std::vector<std::uint64_t> uid{static_cast<std::uint64_t>(world().rank())};
    std::vector<double> x{0.0}, y{0.0}, z{0.0}, ax{1.0}, ay{0.0}, az{0.0};
    gravity::UpdatePolicy calm(0.0, {0.0, 0.0, 0.0}, {1, true, 1e-3, dt, 16, 100});
    long long step = 0;
    std::vector<long long> intervals;
    for (int update = 0; update < 8; ++update) {
        while (!calm.due(world(), uid, x, y, z))
            ++step;
        ax[0] = 1.0 + 0.1 * dt * static_cast<double>(step);
        calm.markUpdated(uid, x, y, z, ax, ay, az);
        calm.adaptInterval(world());
        intervals.push_back(calm.interval());
        ++step;
    }
    // The second update's prediction kept the field (error 1e-3 x 1 step = the budget): kept.
    EXPECT_EQ(intervals, (std::vector<long long>{1, 1, 2, 4, 8, 16, 16, 16}));
    EXPECT_LT(calm.lastPredictionError(), 1e-12);

    gravity::UpdatePolicy rough(0.0, {0.0, 0.0, 0.0}, {8, true, 1e-3, dt, 16, 100});
    for (int update = 0; update < 6; ++update) {
        while (!rough.due(world(), uid, x, y, z)) {
        }
        ax[0] = update % 2 == 0 ? 1.0 : 2.0;
        rough.markUpdated(uid, x, y, z, ax, ay, az);
        rough.adaptInterval(world());
    }
    EXPECT_EQ(rough.interval(), 1);
    EXPECT_GT(rough.lastPredictionError(), 0.1);
}

TEST(UpdateInterval, BadIntervalsNameTheKey) {
    EXPECT_THROW(gravity::UpdatePolicy(0.0, {0.0, 0.0, 0.0}, {-1, false, 0.0, 0.1}),
                 core::InputError);
    EXPECT_THROW(gravity::UpdatePolicy(0.0, {0.0, 0.0, 0.0}, {2, false, 0.0, 0.0}),
                 core::InputError);
    EXPECT_THROW(gravity::UpdatePolicy(0.0, {0.0, 0.0, 0.0}, {1, true, 0.0, 0.1}),
                 core::InputError);
}
