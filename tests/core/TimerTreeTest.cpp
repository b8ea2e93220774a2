// TimerTree: nested scopes on a fake clock (exact, never wall-clock), misuse, and the
// reduction over ranks with rank-dependent, injected durations and different trees.
#include "core/timing/TimerTree.hpp"

#include "core/Error.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

using namespace regolith::core;

TEST(TimerTree, NestedScopesAccumulateSecondsAndCalls) {
    double now = 0.0;
    TimerTree timers([&now] { return now; });
    {
        auto step = timers.scope("step");
        EXPECT_EQ(timers.currentPath(), "step");
        now = 1.0;
        {
            auto sync = timers.scope("sync");
            now = 1.5;
            {
                auto ex = timers.scope("exchange");
                EXPECT_EQ(timers.currentPath(), "step/sync/exchange");
                now = 2.0;
            }
            now = 3.0;
        }
        now = 4.0;
        {
            auto sync = timers.scope("sync"); // same node again
            now = 5.0;
        }
        {
            auto contact = timers.scope("contact");
            now = 5.25;
        }
        now = 6.0;
    }
    EXPECT_EQ(timers.currentPath(), "");
    EXPECT_DOUBLE_EQ(timers.seconds("step"), 6.0);
    EXPECT_DOUBLE_EQ(timers.seconds("step/sync"), 3.0);
    EXPECT_DOUBLE_EQ(timers.seconds("step/sync/exchange"), 0.5);
    EXPECT_DOUBLE_EQ(timers.seconds("step/contact"), 0.25);
    EXPECT_EQ(timers.calls("step"), 1u);
    EXPECT_EQ(timers.calls("step/sync"), 2u);
    EXPECT_EQ(timers.calls("step/sync/exchange"), 1u);
    EXPECT_FALSE(timers.contains("sync")) << "a phase is known by its full path";
    EXPECT_DOUBLE_EQ(timers.seconds("nope/x"), 0.0);
    EXPECT_EQ(timers.paths(), (std::vector<std::string>{"step", "step/sync", "step/sync/exchange",
                                                        "step/contact"}));
}

TEST(TimerTree, StopEndsEarlyOnceAndOnlyInnermost) {
    double now = 0.0;
    TimerTree timers([&now] { return now; });
    {
        auto outer = timers.scope("outer");
        auto inner = timers.scope("inner");
        EXPECT_THROW(outer.stop(), Error) << "inner is still open";
        now = 2.0;
        inner.stop();
        inner.stop(); // no-op
        now = 7.0;
    } // inner's destructor adds nothing more
    EXPECT_DOUBLE_EQ(timers.seconds("outer/inner"), 2.0);
    EXPECT_EQ(timers.calls("outer/inner"), 1u);
    EXPECT_DOUBLE_EQ(timers.seconds("outer"), 7.0);
}

TEST(TimerTree, BadNamesAndResetWhileOpenThrow) {
    TimerTree timers;
    EXPECT_THROW(static_cast<void>(timers.scope("")), Error);
    EXPECT_THROW(static_cast<void>(timers.scope("a/b")), Error);
    EXPECT_THROW(timers.addTime("a//b", 1.0), Error);
    EXPECT_THROW(timers.addTime("", 1.0), Error);
    EXPECT_THROW(timers.addTime("a", -1.0), Error);
    {
        auto s = timers.scope("open");
        EXPECT_THROW(timers.reset(), Error);
    }
    timers.addTime("x/y", 2.0, 3);
    EXPECT_EQ(timers.calls("x/y"), 3u);
    timers.reset();
    EXPECT_TRUE(timers.paths().empty());
}

TEST(TimerTree, ReduceGivesMinAvgMaxOverRanksWithDifferentTrees) {
    Comm world;
    int const r = world.rank();
    int const p = world.size();
    TimerTree timers;
    timers.addTime("step", 10.0 + r);
    timers.addTime("step/sync", r + 1.0, static_cast<std::uint64_t>(r + 1));
    if (r == 0)
        timers.addTime("io", 0.5);
    if (r % 2 == 1)
        timers.addTime("step/gravity", 2.0 * r); // missing on even ranks: counts as 0

    TimerReport const report = timers.reduce(world);
    EXPECT_EQ(report.ranks(), p);

    // Union in tree order: rank 0's paths, then step/gravity (from rank 1) under its parent.
    std::vector<std::string> paths;
    for (auto const& row : report.rows())
        paths.push_back(row.path);
    std::vector<std::string> expectedPaths{"step", "step/sync"};
    if (p > 1)
        expectedPaths.push_back("step/gravity");
    expectedPaths.push_back("io");
    EXPECT_EQ(paths, expectedPaths);

    double sumStep = 0.0;
    double sumSync = 0.0;
    double sumGravity = 0.0;
    double maxGravity = 0.0;
    std::uint64_t sumCalls = 0;
    for (int q = 0; q < p; ++q) {
        sumStep += 10.0 + q;
        sumSync += q + 1.0;
        sumCalls += static_cast<std::uint64_t>(q + 1);
        if (q % 2 == 1) {
            sumGravity += 2.0 * q;
            maxGravity = 2.0 * q;
        }
    }
    auto const* step = report.find("step");
    auto const* sync = report.find("step/sync");
    auto const* io = report.find("io");
    EXPECT_EQ(report.find("sync"), nullptr);
    if (step != nullptr && sync != nullptr && io != nullptr) {
        EXPECT_DOUBLE_EQ(step->min, 10.0);
        EXPECT_DOUBLE_EQ(step->max, 10.0 + (p - 1));
        EXPECT_DOUBLE_EQ(step->avg, sumStep / p);
        EXPECT_EQ(step->depth, 0);
        EXPECT_DOUBLE_EQ(sync->min, 1.0);
        EXPECT_DOUBLE_EQ(sync->max, p);
        EXPECT_DOUBLE_EQ(sync->avg, sumSync / p);
        EXPECT_EQ(sync->callsMin, 1u);
        EXPECT_EQ(sync->callsMax, static_cast<std::uint64_t>(p));
        EXPECT_EQ(sync->callsSum, sumCalls);
        EXPECT_EQ(sync->depth, 1);
        EXPECT_EQ(sync->name, "sync");
        EXPECT_DOUBLE_EQ(io->min, p == 1 ? 0.5 : 0.0);
        EXPECT_DOUBLE_EQ(io->max, 0.5);
        EXPECT_DOUBLE_EQ(io->avg, 0.5 / p);
        EXPECT_EQ(io->callsMin, p == 1 ? 1u : 0u);
    } else {
        ADD_FAILURE() << "missing rows";
    }
    if (p > 1) {
        auto const* gravity = report.find("step/gravity");
        EXPECT_NE(gravity, nullptr);
        if (gravity != nullptr) {
            EXPECT_DOUBLE_EQ(gravity->min, 0.0);
            EXPECT_DOUBLE_EQ(gravity->max, maxGravity);
            EXPECT_DOUBLE_EQ(gravity->avg, sumGravity / p);
        }
    }

    // The table: header + one line per phase, sub-phases indented, and identical everywhere.
    std::string const table = report.format();
    std::istringstream lines(table);
    std::vector<std::string> rows;
    for (std::string line; std::getline(lines, line);)
        rows.push_back(line);
    EXPECT_EQ(rows.size(), expectedPaths.size() + 1);
    if (rows.size() == expectedPaths.size() + 1) {
        EXPECT_EQ(rows[0].rfind("phase", 0), 0u);
        EXPECT_EQ(rows[1].rfind("step ", 0), 0u);
        EXPECT_EQ(rows[2].rfind("  sync ", 0), 0u);
        EXPECT_EQ(rows.back().rfind("io ", 0), 0u);
    }
    auto const all = world.gatherStrings(table, 0);
    for (auto const& t : all)
        EXPECT_EQ(t, table);
}
