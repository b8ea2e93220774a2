#include "apps/regolith/RunPaths.hpp"

#include "apps/common/OutputFile.hpp"
#include "core/Error.hpp"
#include "core/file/Files.hpp"
#include "core/mpi/AgreeOnInputError.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace regolith::apps {

namespace {

namespace fs = std::filesystem;

/// A file the run uses, and what it is to the run ("the scene file", "the --dump file").
struct NamedFile {
    std::string path;
    std::string role;
};

std::string folderOf(std::string const& path) {
    fs::path const dir = fs::path(path).parent_path();
    return dir.empty() ? std::string(".") : dir.string();
}

/// Whether `name` is "checkpoint_<digits>.h5", a name of the checkpoint series.
bool isCheckpointName(std::string const& name) {
    constexpr std::string_view prefix = "checkpoint_";
    constexpr std::string_view suffix = ".h5";
    if (!name.starts_with(prefix) || !name.ends_with(suffix) ||
        name.size() == prefix.size() + suffix.size())
        return false;
    std::string const digits =
        name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    return digits.find_first_not_of("0123456789") == std::string::npos;
}

/// What the run writes under the name `path` in output.dir, or "" (`summaryThere`: the run
/// summary goes to output.dir/summary.json).
std::string writtenInOutputDir(std::string const& path, OutputSection const& output,
                               bool summaryThere) {
    std::string const dir = folderOf(path);
    std::string const name = fs::path(path).filename().string();
    std::string const where = fmt::format("output.dir = \"{}\"", output.dir);
    if (output.dumpEvery > 0 && core::sameFile(dir, (fs::path(output.dir) / "dumps").string()))
        return fmt::format("the particle snapshots' folder '{}/dumps'", output.dir);
    if (core::sameFile(dir, output.dir) && ((summaryThere && name == "summary.json") ||
                                            (output.thermoEvery > 0 && name == "thermo.csv")))
        return fmt::format("the {} file in {}", name, where);
    if (output.vtkEvery > 0) {
        if (core::sameFile(dir, (fs::path(output.dir) / "vtk").string()))
            return fmt::format("the VTK output's folder '{}/vtk'", output.dir);
        if (core::sameFile(dir, output.dir) &&
            (name == "particles.pvd" || name == "blocks.pvd" || name == "grid.pvd"))
            return fmt::format("the VTK series {} in {}", name, where);
    }
    if (output.checkpointEvery > 0 && core::sameFile(dir, output.dir) && isCheckpointName(name))
        return fmt::format("a checkpoint's name in {}", where);
    return {};
}

} // namespace

std::string summaryPath(core::CliOptions const& options, SceneDescription const& scene) {
    if (!options.jsonPath.empty())
        return options.jsonPath;
    return (fs::path(scene.output.dir) / "summary.json").string();
}

std::string thermoPath(SceneDescription const& scene) {
    return (fs::path(scene.output.dir) / "thermo.csv").string();
}

bool writesIntoOutputDir(core::CliOptions const& options, SceneDescription const& scene) {
    OutputSection const& o = scene.output;
    return options.jsonPath.empty() || o.vtkEvery > 0 || o.checkpointEvery > 0 ||
           o.thermoEvery > 0 || o.dumpEvery > 0;
}

void checkRunPaths(core::Comm const& world, core::CliOptions const& options,
                   SceneDescription const& scene) {
    core::agreeOnInputError(world, [&] {
        if (world.rank() != 0)
            return;
        std::vector<NamedFile> inputs;
        if (!options.scenePath.empty())
            inputs.push_back({options.scenePath, "the scene file"});
        for (std::size_t k = 0; k < scene.particles.size(); ++k)
            if (auto const* file = std::get_if<particles::FileSpec>(&scene.particles[k].kind))
                inputs.push_back(
                    {file->path, fmt::format("the CSV file of particles[{}].path", k)});
        if (!options.restartPath.empty())
            inputs.push_back({options.restartPath, "the --restart checkpoint"});
        std::vector<NamedFile> outputs;
        if (!options.jsonPath.empty())
            outputs.push_back({options.jsonPath, "--json"});
        if (!options.dumpPath.empty())
            outputs.push_back({options.dumpPath, "--dump"});
        for (std::size_t o = 0; o < outputs.size(); ++o) {
            std::string const& path = outputs[o].path;
            std::string const& option = outputs[o].role;
            if (writtenInPlace(path))
                continue;
            auto const refuse = [&](std::string const& what) {
                throw core::InputError(fmt::format("{} {}: names {}, which the run would "
                                                   "overwrite; choose another file",
                                                   option, path, what));
            };
            for (NamedFile const& input : inputs)
                if (core::sameFile(path, input.path))
                    refuse(fmt::format("{} ('{}'), an input of the run", input.role, input.path));
            for (std::size_t other = 0; other < o; ++other)
                if (core::sameFile(path, outputs[other].path))
                    refuse(fmt::format("the {} file too", outputs[other].role));
            if (std::string const what =
                    writtenInOutputDir(path, scene.output, options.jsonPath.empty());
                !what.empty())
                refuse(what);
        }
    });
}

} // namespace regolith::apps
