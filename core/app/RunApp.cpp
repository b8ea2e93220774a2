#include "core/app/RunApp.hpp"

#include "core/Error.hpp"
#include "core/config/ConfigFile.hpp"
#include "core/log/Log.hpp"
#include "core/log/Printable.hpp"
#include "core/memory/HeapPolicy.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>

namespace regolith::core {

namespace {

constexpr int kExitInputError = 2;

void printInputError(std::string_view appName, std::string_view message) {
    // One "app: error:" prefix per line, so a list of unknown keys reads like compiler output.
    while (!message.empty() && message.back() == '\n')
        message.remove_suffix(1);
    std::size_t start = 0;
    while (start <= message.size()) {
        auto end = message.find('\n', start);
        if (end == std::string_view::npos)
            end = message.size();
        // A NUL byte from a file would end the line early: control bytes are escaped.
        std::string const line = printable(message.substr(start, end - start));
        std::fprintf(stderr, "%.*s: error: %.*s\n", static_cast<int>(appName.size()),
                     appName.data(), static_cast<int>(line.size()), line.data());
        start = end + 1;
    }
    std::fflush(stderr);
}

[[noreturn]] void abortJob(std::string_view appName, int rank, char const* what) {
    std::fprintf(stderr, "%.*s: [rank %d] internal error: %s\n", static_cast<int>(appName.size()),
                 appName.data(), rank, what);
    std::fflush(stderr);
    std::fflush(stdout);
    MPI_Abort(MPI_COMM_WORLD, 1);
    std::_Exit(1); // MPI_Abort does not return; this keeps the promise if it ever did
}

} // namespace

int runApp(int argc, char** argv, std::string_view appName, std::string_view defaultSceneToml,
           std::function<int(AppContext&)> const& body) {
    useReturningHeap(); // peak memory: large set-up temporaries must not stay resident
    std::optional<MpiEnvironment> mpi;
    try {
        mpi.emplace(argc, argv);
    } catch (std::exception const& e) {
        std::fprintf(stderr, "%.*s: error: cannot initialise MPI: %s\n",
                     static_cast<int>(appName.size()), appName.data(), e.what());
        return 1;
    }
    int rank = 0;
    try {
        Comm const world;
        rank = world.rank();
        CliOptions const options = parseCommandLine(argc, argv, appName);
        if (options.help || options.version) {
            if (world.rank() == 0) {
                std::string const text =
                    options.help ? usage(appName) : fmt::format("{} {}\n", appName, version());
                std::fputs(text.c_str(), stdout);
                std::fflush(stdout);
            }
            return 0;
        }
        log::init(world, options.quiet ? log::Level::Warn : log::Level::Info);
        bool const embedded = options.scenePath.empty();
        ConfigTable scene =
            embedded ? ConfigTable::fromString(defaultSceneToml, "<embedded default scene>")
                     : loadConfigFile(world, options.scenePath);
        applySceneOptions(options, scene);
        AppContext context{world,
                           options,
                           scene,
                           embedded ? "<embedded default scene>" : options.scenePath,
                           std::string(appName),
                           defaultSceneToml};
        int const code = body(context);
        std::fflush(stdout);
        return code;
    } catch (InputError const& e) {
        std::fflush(stdout);
        if (rank == 0)
            printInputError(appName, e.what());
        // Every rank is here (by contract an InputError is thrown alike everywhere). Wait for
        // rank 0's message: mpiexec kills the job as soon as one rank exits non-zero.
        MPI_Barrier(MPI_COMM_WORLD);
        return kExitInputError;
    } catch (RankInputError const& e) {
        std::fflush(stdout);
        printInputError(appName, fmt::format("[rank {}] {}", rank, e.what()));
        MPI_Abort(MPI_COMM_WORLD, kExitInputError);
        std::_Exit(kExitInputError);
    } catch (std::exception const& e) {
        abortJob(appName, rank, e.what());
    } catch (...) {
        abortJob(appName, rank, "unknown exception");
    }
}

} // namespace regolith::core
