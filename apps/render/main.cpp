// regolith-render: a PNG of one step of a run's VTK output, without a display (VTK off-screen
// rendering; under xvfb-run where there is no X server). Grains are spheres of their radius
// coloured by speed (blue slow, red fast), blocks are outlines coloured by owner rank.
//
//   regolith-render out/particles.pvd [--step K] [--png FILE] [--size W H]
//
// K indexes the series (default: the last entry; negative counts from the end). The block
// outlines come from blocks.pvd next to the particles series, if there is one. FILE defaults
// to <series dir>/snapshot.png. Exit code 0, or 2 with one message.
#include "core/Error.hpp"
#include "io/render/Snapshot.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace {

using namespace regolith;
namespace fs = std::filesystem;

struct Arguments {
    std::string series;
    long step = -1;
    std::string png;
    int width = 1200;
    int height = 900;
};

constexpr std::string_view kUsage =
    "usage: regolith-render SERIES.pvd [--step K] [--png FILE] [--size W H]\n";

long number(std::vector<std::string> const& args, std::size_t i, std::string_view option) {
    if (i >= args.size())
        throw core::InputError(fmt::format("{} needs a value", option));
    try {
        std::size_t used = 0;
        long const v = std::stol(args[i], &used);
        if (used == args[i].size())
            return v;
    } catch (std::exception const&) {
    }
    throw core::InputError(fmt::format("{} {}: expected an integer", option, args[i]));
}

Arguments parse(std::vector<std::string> const& args) {
    Arguments a;
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--step") {
            a.step = number(args, ++i, "--step");
        } else if (args[i] == "--png" && i + 1 < args.size()) {
            a.png = args[++i];
        } else if (args[i] == "--size") {
            a.width = static_cast<int>(number(args, ++i, "--size"));
            a.height = static_cast<int>(number(args, ++i, "--size"));
            if (a.width <= 0 || a.height <= 0 || a.width > 16384 || a.height > 16384)
                throw core::InputError("--size: expected two integers in [1, 16384]");
        } else if (a.series.empty() && !args[i].starts_with("--")) {
            a.series = args[i];
        } else {
            throw core::InputError(fmt::format("unexpected argument '{}'", args[i]));
        }
    }
    if (a.series.empty())
        throw core::InputError("no series given");
    return a;
}

/// The entry `step` of a series (negative: from the end).
io::SeriesEntry pick(std::vector<io::SeriesEntry> const& series, long step,
                     std::string const& path) {
    auto const n = static_cast<long>(series.size());
    long const k = step < 0 ? n + step : step;
    if (k < 0 || k >= n)
        throw core::InputError(
            fmt::format("--step {}: '{}' has {} entries (0 to {})", step, path, n, n - 1));
    return series[static_cast<std::size_t>(k)];
}

int run(Arguments const& a) {
    fs::path const dir = fs::path(a.series).parent_path();
    auto const particles = io::readSeries(a.series);
    io::SeriesEntry const entry = pick(particles, a.step, a.series);
    io::SnapshotOptions options;
    options.particles = (dir / entry.file).string();
    options.png = a.png.empty() ? (dir / "snapshot.png").string() : a.png;
    options.width = a.width;
    options.height = a.height;
    fs::path const blocksSeries = dir / "blocks.pvd";
    if (fs::is_regular_file(blocksSeries))
        for (io::SeriesEntry const& b : io::readSeries(blocksSeries.string()))
            if (b.time == entry.time)
                options.blocks = (dir / b.file).string();
    io::renderSnapshot(options);
    fmt::print("regolith-render: {} (time {}) -> {}\n", options.particles, entry.time, options.png);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    std::vector<std::string> const args(argv + 1, argv + argc);
    if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
        fmt::print("{}", kUsage);
        return 0;
    }
    try {
        return run(parse(args));
    } catch (core::InputError const& e) {
        fmt::print(stderr, "regolith-render: error: {}\n{}", e.what(), kUsage);
        return 2;
    }
}
