#include "core/log/Log.hpp"

#include "core/Error.hpp"

#include <spdlog/logger.h>
#include <spdlog/sinks/stdout_sinks.h>

#include <memory>
#include <string>

namespace regolith::core::log {

namespace {

/// This process's logging state: the rank copied at init(), never a communicator.
struct State {
    int rank = 0;
    Level level = Level::Info;
    bool allRanks = false;
    std::shared_ptr<spdlog::logger> out; ///< debug, info, warn
    std::shared_ptr<spdlog::logger> err; ///< error
};

std::shared_ptr<spdlog::logger> makeLogger(char const* name, spdlog::sink_ptr sink) {
    auto logger = std::make_shared<spdlog::logger>(name, std::move(sink));
    logger->set_pattern("%v"); // the prefix is composed in write()
    logger->set_level(spdlog::level::trace);
    logger->flush_on(spdlog::level::err);
    return logger;
}

State makeDefaultState() {
    State s;
    s.out = makeLogger("regolith", std::make_shared<spdlog::sinks::stdout_sink_mt>());
    s.err = makeLogger("regolith.err", std::make_shared<spdlog::sinks::stderr_sink_mt>());
    return s;
}

State& state() {
    static State s = makeDefaultState();
    return s;
}

spdlog::level::level_enum toSpdlog(Level level) {
    switch (level) {
    case Level::Debug:
        return spdlog::level::debug;
    case Level::Info:
        return spdlog::level::info;
    case Level::Warn:
        return spdlog::level::warn;
    case Level::Error:
        return spdlog::level::err;
    case Level::Off:
        break;
    }
    return spdlog::level::off;
}

char const* label(Level level) {
    switch (level) {
    case Level::Debug:
        return "debug";
    case Level::Info:
        return "info";
    case Level::Warn:
        return "warn";
    case Level::Error:
        return "error";
    case Level::Off:
        break;
    }
    return "off";
}

} // namespace

void init(Comm const& comm, Level level, bool allRanks) {
    State s = makeDefaultState();
    s.rank = comm.rank();
    s.level = level;
    s.allRanks = allRanks;
    state() = std::move(s);
}

void init(Comm const& comm, Level level, bool allRanks, spdlog::sink_ptr sink) {
    State s;
    s.rank = comm.rank();
    s.level = level;
    s.allRanks = allRanks;
    s.out = makeLogger("regolith", sink);
    s.err = makeLogger("regolith.err", std::move(sink));
    state() = std::move(s);
}

Level parseLevel(std::string_view name) {
    for (Level const l : {Level::Debug, Level::Info, Level::Warn, Level::Error, Level::Off})
        if (name == label(l))
            return l;
    throw InputError(std::string("unknown log level '") + std::string(name) +
                     "' (expected debug, info, warn, error or off)");
}

bool enabled(Level level) {
    State const& s = state();
    if (level == Level::Off || level < s.level)
        return false;
    return level == Level::Error || s.allRanks || s.rank == 0;
}

void write(Level level, std::string_view message) {
    if (!enabled(level))
        return;
    State const& s = state();
    std::string const prefix = (s.allRanks || level == Level::Error)
                                   ? fmt::format("[rank {}] [{}] ", s.rank, label(level))
                                   : fmt::format("[{}] ", label(level));
    auto const& logger = level == Level::Error ? s.err : s.out;
    logger->log(toSpdlog(level), "{}{}", prefix, message);
}

void flush() {
    state().out->flush();
    state().err->flush();
}

} // namespace regolith::core::log
