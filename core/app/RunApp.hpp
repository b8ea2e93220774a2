#pragma once
/// The entry point every Regolith app goes through: MPI, command line, scene, error handling.
#include "core/app/CliOptions.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/mpi/Comm.hpp"

#include <functional>
#include <string>
#include <string_view>

namespace regolith::core {

/// What an app body receives from runApp.
struct AppContext {
    Comm const& world;         ///< MPI_COMM_WORLD; subsystems duplicate it
    CliOptions const& options; ///< the parsed command line
    ConfigTable& scene;        ///< root of the scene, command-line overrides applied
    std::string sceneName;     ///< the scene file, or "<embedded default scene>"
    std::string appName;
    std::string_view defaultScene; ///< the app's embedded scene text (used without a file)

    [[nodiscard]] bool isRoot() const { return world.rank() == 0; }
};

/// Runs an app: initialises MPI, parses the command line (`--help` prints the usage on rank 0
/// and returns 0), sets up core::log (level Info, Warn with `--quiet`), loads the scene (the file
/// given, read once by rank 0, or `defaultSceneToml` without one), applies
/// `--set`/`--steps`/`--output`, and calls `body`, whose return value becomes the exit code. MPI is
/// finalised before returning.
///
/// Errors: a core::InputError (bad scene, option or file; by contract thrown alike on every
/// rank) makes rank 0 print "<appName>: error: <message>" once (one such line per line of
/// the message) and every rank return 2, so no rank waits in a collective. Any other
/// exception is a one-rank failure: that rank prints "<appName>: [rank N] internal error:
/// <message>" and calls MPI_Abort(MPI_COMM_WORLD, 1), which ends every rank.
/// COLLECTIVE over MPI_COMM_WORLD (it is the whole program).
int runApp(int argc, char** argv, std::string_view appName, std::string_view defaultSceneToml,
           std::function<int(AppContext&)> const& body);

} // namespace regolith::core
