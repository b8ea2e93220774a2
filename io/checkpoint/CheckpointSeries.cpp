#include "io/checkpoint/CheckpointSeries.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <utility>

namespace regolith::io {

namespace {

constexpr std::string_view kPrefix = "checkpoint_";
constexpr std::string_view kSuffix = ".h5";

/// The step of a checkpoint file name, or -1 if the name is not one.
std::int64_t stepOf(std::string const& name) {
    if (name.size() <= kPrefix.size() + kSuffix.size() || !name.starts_with(kPrefix) ||
        !name.ends_with(kSuffix))
        return -1;
    std::string const digits =
        name.substr(kPrefix.size(), name.size() - kPrefix.size() - kSuffix.size());
    if (digits.size() > 18 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return -1;
    return std::stoll(digits);
}

} // namespace

std::string checkpointPath(std::string const& dir, std::int64_t step) {
    return (std::filesystem::path(dir) / fmt::format("{}{:08d}{}", kPrefix, step, kSuffix))
        .string();
}

std::vector<std::string> rotateCheckpoints(std::string const& dir, std::int64_t keep) {
    std::vector<std::string> removed;
    if (keep <= 0)
        return removed;
    std::vector<std::pair<std::int64_t, std::filesystem::path>> found;
    std::error_code ec;
    for (auto const& entry : std::filesystem::directory_iterator(dir, ec)) {
        std::int64_t const step = stepOf(entry.path().filename().string());
        if (step >= 0 && entry.is_regular_file(ec))
            found.emplace_back(step, entry.path());
    }
    if (found.size() <= static_cast<std::size_t>(keep))
        return removed;
    std::sort(found.begin(), found.end());
    for (std::size_t k = 0; k + static_cast<std::size_t>(keep) < found.size(); ++k)
        if (std::filesystem::remove(found[k].second, ec))
            removed.push_back(found[k].second.string());
    return removed;
}

} // namespace regolith::io
