// When the run's force-error checks are armed (ForceErrorMonitor.hpp): after every n-th update,
// or "auto" after the first update of each interval of steps; a check taken disarms and its
// samples pool into the run's median and 99th percentile.
#include "coupling/gravity/ForceErrorMonitor.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace regolith;

TEST(ForceErrorMonitor, ArmsAfterEveryNthUpdate) {
    coupling::ForceErrorMonitor m({3, 0, 100});
    m.afterStep(true, 1, 1);
    m.afterStep(false, 1, 2);
    m.afterStep(true, 2, 3);
    EXPECT_FALSE(m.armed());
    m.afterStep(true, 3, 4);
    EXPECT_TRUE(m.armed());
    m.record({0.1, 0.2, 0.3});
    EXPECT_FALSE(m.armed());
    m.afterStep(true, 6, 9);
    m.record({0.4});
    EXPECT_EQ(m.checks(), 2);
    EXPECT_EQ(m.stats().count, 4);
    EXPECT_DOUBLE_EQ(m.stats().median, 0.2);
    EXPECT_DOUBLE_EQ(m.stats().max, 0.4);
}

TEST(ForceErrorMonitor, AutoArmsOncePerIntervalOfSteps) {
    coupling::ForceErrorMonitor m({0, 10, 100});
    m.afterStep(true, 1, 1); // the set-up's update
    EXPECT_TRUE(m.armed());
    m.record({0.0});
    for (long long step = 2; step <= 10; ++step) {
        m.afterStep(true, step, step);
        EXPECT_FALSE(m.armed()) << step;
    }
    m.afterStep(false, 10, 11); // no update: nothing to judge yet
    EXPECT_FALSE(m.armed());
    m.afterStep(true, 11, 12);
    EXPECT_TRUE(m.armed());
    m.record({0.0});
    m.afterStep(true, 12, 35); // past two intervals at once: one check
    EXPECT_TRUE(m.armed());
    m.record({0.0});
    m.afterStep(true, 13, 36);
    EXPECT_FALSE(m.armed());
}

TEST(ForceErrorMonitor, NeverWithoutASchedule) {
    coupling::ForceErrorMonitor m({0, 0, 100});
    for (long long step = 1; step <= 5; ++step)
        m.afterStep(true, step, step);
    EXPECT_FALSE(m.armed());
    EXPECT_EQ(m.checks(), 0);
}
