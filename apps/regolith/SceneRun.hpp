#pragma once
/// The scene run every app shares (docs/design.md, "The time step" and "Contracts"): reads the
/// scene in `ctx.scene`, builds the forest, generates the grains (or restores a checkpoint's),
/// refuses a scene the chosen synchronisation cannot simulate, runs the steps as a
/// coupling::Simulation with the scene's outputs as its observers, and writes the run summary
/// (--json) and the dump (--dump).
#include "core/app/RunApp.hpp"
#include "coupling/simulation/Simulation.hpp"

#include <cstdint>
#include <vector>

namespace regolith::apps {

/// What an app adds to the scene run without editing it (docs/guide/library.md): forces or
/// torques of its own in every force computation, and observers after the steps they name
/// (after the scene's own outputs; the grains complete, velocities writable). The run's
/// checkpoints, restart, VTK output and summary stay the driver's.
struct SceneHooks {
    struct Observer {
        std::int64_t every = 1; ///< after every step whose number is a multiple of this
        coupling::Simulation::Observer observe;
    };
    std::vector<coupling::Simulation::BodyForces> bodyForces;
    std::vector<Observer> observers;
};

/// The body for core::runApp: returns the exit code (0). Throws core::InputError for a bad
/// scene (runApp reports it on every rank). COLLECTIVE over ctx.world.
int runScene(core::AppContext& ctx);
/// The same with an app's hooks: `core::runApp(argc, argv, name, scene, [&](auto& ctx) {
/// return apps::runSceneWith(ctx, hooks); })`.
int runSceneWith(core::AppContext& ctx, SceneHooks const& hooks);

} // namespace regolith::apps
