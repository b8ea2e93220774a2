#include "io/checkpoint/CheckpointSeries.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <string_view>
#include <system_error>

namespace regolith::io {

namespace {

constexpr std::string_view kPrefix = "checkpoint_";
constexpr std::string_view kSuffix = ".h5";

} // namespace

std::string checkpointPath(std::string const& dir, std::int64_t step) {
    return (std::filesystem::path(dir) / fmt::format("{}{:08d}{}", kPrefix, step, kSuffix))
        .string();
}

std::vector<std::string> rotateCheckpoints(std::vector<std::string>& written, std::int64_t keep) {
    std::vector<std::string> removed;
    if (keep <= 0 || written.size() <= static_cast<std::size_t>(keep))
        return removed;
    auto const stale = written.end() - static_cast<std::ptrdiff_t>(keep);
    std::error_code ec;
    for (auto it = written.begin(); it != stale; ++it)
        if (std::filesystem::remove(*it, ec))
            removed.push_back(*it);
    written.erase(written.begin(), stale);
    return removed;
}

} // namespace regolith::io
