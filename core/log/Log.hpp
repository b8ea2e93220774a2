#pragma once
/// Logging with levels and rank prefixes, on spdlog, fmt-style:
///
///     core::log::init(world, core::log::Level::Info);
///     core::log::info("{} particles on {} blocks", n, blocks);   // rank 0 only
///     core::log::error("cannot open {}", path);                  // every rank, "[rank N]"
///
/// Filtering: a message below the level is dropped. By default only rank 0 prints debug, info
/// and warn; errors print on every rank. With `allRanks` every rank prints every level.
/// Prefix: "[rank N] " when `allRanks` or for errors, then "[level] ", then the message.
/// Output: errors to stderr, the rest to stdout, unless a sink is injected (tests).
///
/// init() copies the rank only; no communicator is kept. Before init() every process behaves
/// as rank 0 at level Info. Thread-safe sinks; init() itself is not thread-safe.
#include "core/mpi/Comm.hpp"

#include <fmt/format.h>
#include <spdlog/common.h>

#include <string_view>
#include <utility>

namespace regolith::core::log {

enum class Level { Debug, Info, Warn, Error, Off };

/// Sets this rank's filter and the default sinks (stdout, errors to stderr). Not collective.
void init(Comm const& comm, Level level, bool allRanks = false);
/// As init(), writing every level to `sink` (e.g. an spdlog ostream sink in a test).
void init(Comm const& comm, Level level, bool allRanks, spdlog::sink_ptr sink);

/// Parses "debug", "info", "warn", "error" or "off"; throws core::InputError otherwise.
[[nodiscard]] Level parseLevel(std::string_view name);

/// Whether a message at `level` is printed on this rank (to skip costly arguments).
[[nodiscard]] bool enabled(Level level);

/// Prints an already formatted message if enabled(level), with the prefix described above.
void write(Level level, std::string_view message);

/// Flushes the sinks.
void flush();

template <class... Args>
void debug(fmt::format_string<Args...> format, Args&&... args) {
    if (enabled(Level::Debug))
        write(Level::Debug, fmt::format(format, std::forward<Args>(args)...));
}
template <class... Args>
void info(fmt::format_string<Args...> format, Args&&... args) {
    if (enabled(Level::Info))
        write(Level::Info, fmt::format(format, std::forward<Args>(args)...));
}
template <class... Args>
void warn(fmt::format_string<Args...> format, Args&&... args) {
    if (enabled(Level::Warn))
        write(Level::Warn, fmt::format(format, std::forward<Args>(args)...));
}
template <class... Args>
void error(fmt::format_string<Args...> format, Args&&... args) {
    if (enabled(Level::Error))
        write(Level::Error, fmt::format(format, std::forward<Args>(args)...));
}

} // namespace regolith::core::log
