#pragma once
/// The scene run every app shares (docs/design.md, "The time step" and "Contracts"): reads the
/// scene in `ctx.scene`, builds the forest, generates the grains, refuses a scene the chosen
/// synchronisation cannot simulate, runs `time.steps` steps and writes the run summary
/// (--json) and the dump (--dump).
#include "core/app/RunApp.hpp"

namespace regolith::apps {

/// The body for core::runApp: returns the exit code (0). Throws core::InputError for a bad
/// scene (runApp reports it on every rank). COLLECTIVE over ctx.world.
int runScene(core::AppContext& ctx);

} // namespace regolith::apps
