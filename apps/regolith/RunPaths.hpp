#pragma once
/// The files a `regolith` run reads and writes, checked against each other before the first
/// step: an output that names an input (the scene file, a [[particles]] CSV file, the
/// --restart checkpoint) or another output would overwrite it after the run, silently.
#include "apps/regolith/SceneSections.hpp"
#include "core/app/CliOptions.hpp"
#include "core/mpi/Comm.hpp"

#include <string>

namespace regolith::apps {

/// Where the run summary goes: --json if given, else output.dir/summary.json. Not collective.
[[nodiscard]] std::string summaryPath(core::CliOptions const& options,
                                      SceneDescription const& scene);
/// output.dir/thermo.csv (ThermoLog.hpp). Not collective.
[[nodiscard]] std::string thermoPath(SceneDescription const& scene);

/// Throws core::InputError on every rank, naming the option and both uses of the file, if
/// --json or --dump names an input of the run, the other of them, or a file the run writes
/// in output.dir (the VTK series and pieces with output.vtk_every > 0, the checkpoints with
/// output.checkpoint_every > 0, thermo.csv with output.thermo_every > 0, summary.json without
/// --json). Files written in place (a FIFO, /dev/null, /dev/stdout) may
/// be shared. Rank 0 looks; COLLECTIVE over `world`.
void checkRunPaths(core::Comm const& world, core::CliOptions const& options,
                   SceneDescription const& scene);

/// Whether the run writes into output.dir: the summary there (no --json), VTK, checkpoints,
/// thermo.csv or particle snapshots. Not collective.
[[nodiscard]] bool writesIntoOutputDir(core::CliOptions const& options,
                                       SceneDescription const& scene);

} // namespace regolith::apps
