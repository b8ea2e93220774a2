#pragma once
/// The command line shared by every Regolith app (docs/design.md, "Command line"):
///   app [scene.toml] [--set section.key=value]... [--json summary.json] [--dump final.csv]
///       [--steps N] [--output DIR] [--restart CHECKPOINT] [--quiet]
/// CLI11 does the parsing; it stays private to regolith::core.
#include "core/config/ConfigTable.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace regolith::core {

struct CliOptions {
    std::string scenePath;              ///< empty: run the app's embedded default scene
    std::vector<std::string> overrides; ///< `--set` assignments, in command-line order
    std::string jsonPath;               ///< `--json`: run summary, written by rank 0
    std::string dumpPath;               ///< `--dump`: final masters as CSV
    std::string outputDir;              ///< `--output`: overrides output.dir
    std::string restartPath;            ///< `--restart`: checkpoint to start from
    std::optional<std::int64_t> steps;  ///< `--steps`: overrides time.steps
    bool quiet = false;                 ///< `--quiet`: only warnings and errors
    bool help = false;                  ///< `-h`/`--help` was given: print usage, exit 0
    bool version = false;               ///< `--version` was given: print the version, exit 0
};

/// The program's version (the CMake project's), e.g. "0.1.0".
[[nodiscard]] std::string_view version();

/// Parses `argv[1..argc)`. Throws InputError naming the offending argument for an unknown
/// option, a missing option value or a malformed number (the same on every rank, since every
/// rank gets the same argv). Not collective.
[[nodiscard]] CliOptions parseCommandLine(int argc, char const* const* argv,
                                          std::string_view appName);

/// The usage text printed by `--help`.
[[nodiscard]] std::string usage(std::string_view appName);

/// Applies the options that edit the scene to `scene` (its root): every `--set` in order,
/// then `--steps N` as time.steps and `--output DIR` as output.dir, each reported as coming
/// from its option ("--steps -3: time.steps: ..."). Throws InputError for a bad `--set`.
void applySceneOptions(CliOptions const& options, ConfigTable& scene);

} // namespace regolith::core
