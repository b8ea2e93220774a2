#include "io/checkpoint/CheckpointSeries.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
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

std::vector<std::string> checkpointsToReplace(std::string const& dir, std::int64_t every,
                                              std::int64_t firstStep, std::int64_t lastStep) {
    std::vector<std::string> out;
    std::error_code ec;
    if (every <= 0 || !std::filesystem::is_directory(dir, ec))
        return out;
    for (auto const& entry : std::filesystem::directory_iterator(dir, ec)) {
        std::string const name = entry.path().filename().string();
        if (!name.starts_with(kPrefix) || !name.ends_with(kSuffix))
            continue;
        std::string const digits =
            name.substr(kPrefix.size(), name.size() - kPrefix.size() - kSuffix.size());
        if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
            digits.size() > 18)
            continue;
        std::int64_t const step = std::stoll(digits);
        if (step > firstStep && step <= lastStep && step % every == 0 &&
            entry.path().string() == checkpointPath(dir, step))
            out.push_back(name);
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::string notACheckpointFile(std::string const& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        return "which is not a file";
    static constexpr char kSignature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
    char head[8] = {};
    std::ifstream in(path, std::ios::binary);
    if (!in.read(head, sizeof head) || !std::equal(head, head + 8, kSignature))
        return "which is not an HDF5 file";
    return {};
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
