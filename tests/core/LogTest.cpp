// Logging: rank-0-only filtering, errors on every rank, "[rank N]" prefixes, levels; output
// captured through an injected spdlog ostream sink.
#include "core/log/Log.hpp"

#include "core/Error.hpp"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

#include <memory>
#include <sstream>
#include <string>

using namespace regolith::core;

namespace {

/// Captures log output for one test, restoring the default sinks afterwards.
class LogCapture {
public:
    LogCapture(Comm const& comm, log::Level level, bool allRanks)
        : m_comm(comm) {
        log::init(comm, level, allRanks, std::make_shared<spdlog::sinks::ostream_sink_mt>(m_out));
    }
    ~LogCapture() { log::init(m_comm, log::Level::Info); }
    LogCapture(LogCapture const&) = delete;
    LogCapture& operator=(LogCapture const&) = delete;

    std::string text() {
        log::flush();
        return m_out.str();
    }

private:
    Comm const& m_comm;
    std::ostringstream m_out;
};

void logOneOfEach() {
    log::debug("d {}", 1);
    log::info("i {} {}", 2, "two");
    log::warn("w {:.1f}", 3.0);
    log::error("e {}", "four");
}

} // namespace

TEST(Log, DefaultPrintsOnRankZeroAndErrorsEverywhere) {
    Comm world;
    int const r = world.rank();
    LogCapture capture(world, log::Level::Info, false);
    logOneOfEach();
    std::string const expected = r == 0 ? "[info] i 2 two\n[warn] w 3.0\n[rank 0] [error] e four\n"
                                        : "[rank " + std::to_string(r) + "] [error] e four\n";
    EXPECT_EQ(capture.text(), expected);
    EXPECT_EQ(log::enabled(log::Level::Info), r == 0);
    EXPECT_FALSE(log::enabled(log::Level::Debug));
    EXPECT_TRUE(log::enabled(log::Level::Error));
}

TEST(Log, AllRanksPrefixesEveryLine) {
    Comm world;
    std::string const prefix = "[rank " + std::to_string(world.rank()) + "] ";
    LogCapture capture(world, log::Level::Debug, true);
    logOneOfEach();
    EXPECT_EQ(capture.text(), prefix + "[debug] d 1\n" + prefix + "[info] i 2 two\n" + prefix +
                                  "[warn] w 3.0\n" + prefix + "[error] e four\n");
}

TEST(Log, LevelsFilter) {
    Comm world;
    {
        LogCapture capture(world, log::Level::Error, false);
        logOneOfEach();
        EXPECT_EQ(capture.text(), "[rank " + std::to_string(world.rank()) + "] [error] e four\n");
    }
    {
        LogCapture capture(world, log::Level::Off, true);
        logOneOfEach();
        EXPECT_EQ(capture.text(), "");
        EXPECT_FALSE(log::enabled(log::Level::Error));
    }
}

TEST(Log, ParseLevel) {
    EXPECT_EQ(log::parseLevel("debug"), log::Level::Debug);
    EXPECT_EQ(log::parseLevel("info"), log::Level::Info);
    EXPECT_EQ(log::parseLevel("warn"), log::Level::Warn);
    EXPECT_EQ(log::parseLevel("error"), log::Level::Error);
    EXPECT_EQ(log::parseLevel("off"), log::Level::Off);
    EXPECT_THROW(static_cast<void>(log::parseLevel("verbose")), InputError);
}
