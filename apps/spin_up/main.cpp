// spin_up: a self-gravitating rubble pile spun up to failure ([spin_up]) or passing a point
// mass on a hyperbola ([flyby]), recording its spin, shape, mass shed and largest remnant
// ([pile]) to a CSV file (docs/guide/rubble-piles.md). The scene driver with the rubble-pile
// recorder's body forces and observer as hooks: the scene's keys, checkpoints and --restart,
// VTK output and the run summary are the driver's. Runs a scene file, or scenes/spin-up.toml
// (compiled in) without one. Usage: spin_up --help.
#include "apps/regolith/SceneRun.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "apps/spin_up/PileRecorder.hpp"
#include "apps/spin_up/RubblePileSections.hpp"
#include "core/Error.hpp"
#include "core/app/RunApp.hpp"
#include "io/checkpoint/CheckpointReader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>

namespace regolith::apps {

std::string_view spinUpScene();

namespace {

std::string spinText(std::optional<double> spin) {
    return spin ? fmt::format("{:.3f} omega_c", *spin) : std::string("not reached");
}

/// The pile's scales, once measured (and the fly-by's pass).
void printReference(PileRecorder const& recorder, double dt) {
    PileReference const& r = recorder.reference();
    double const density = r.mass / (4.0 / 3.0 * std::numbers::pi * std::pow(r.bulkRadius, 3));
    fmt::print("rubble pile: mass {:.6g}, bulk radius {:.6g}, bulk density {:.6g}, omega_c "
               "{:.6g} (period {:.6g}), spin {:.3f} omega_c\n",
               r.mass, r.bulkRadius, density, r.omegaC, 2.0 * std::numbers::pi / r.omegaC,
               r.spin / r.omegaC);
    if (HyperbolicPass const* pass = recorder.pass())
        fmt::print("fly-by: the pass takes {:.6g} ({} steps), v_inf {:.6g}\n", pass->duration(),
                   static_cast<long long>(pass->duration() / dt), pass->speedAtInfinity());
}

int runRubblePile(core::AppContext& ctx) {
    RubblePileScene piles = parseRubblePileScene(ctx.scene); // its keys known before the driver's
    SceneDescription const scene = parseScene(ctx.scene, ctx.options.scenePath);
    if (scene.time.dtAuto)
        ctx.scene.table("time").fail("dt", "spin_up needs a number (the spin-up rate and the "
                                           "fly-by's clock are checked against it), not \"auto\"");
    std::filesystem::path const file = std::filesystem::path(scene.output.dir) / piles.pile.file;
    std::filesystem::create_directories(file.parent_path());
    piles.pile.file = file.string();

    PileRecorder recorder(ctx.world, piles, scene.gravity.G, scene.time.dt);
    if (!ctx.options.restartPath.empty())
        recorder.resume(io::readCheckpoint(ctx.world, ctx.options.restartPath).info.step,
                        ctx.options.restartPath);
    SceneHooks hooks;
    hooks.bodyForces.emplace_back(
        [&recorder](particles::LocalParticles& grains) { recorder.addForces(grains); });
    bool printed = false;
    hooks.observers.push_back({piles.pile.recordEvery, [&](coupling::Simulation& s) {
                                   recorder.requireStep(s.stepsDone());
                                   if (recorder.record(s.grains()) && !printed) {
                                       printed = true;
                                       if (ctx.isRoot() && !ctx.options.quiet)
                                           printReference(recorder, scene.time.dt);
                                   }
                               }});
    int const code = runSceneWith(ctx, hooks);
    std::optional<PileRecord> const& last = recorder.lastRecord();
    if (ctx.isRoot() && !ctx.options.quiet && last) {
        if (piles.spinUp)
            fmt::print("rubble pile: failure (peak spin) {}; mass shed from {}\n",
                       spinText(recorder.failureSpin()), spinText(recorder.sheddingOnset()));
        fmt::print("rubble pile at t = {:.6g}: spin {:.3f} omega_c, shed {:.4f}, largest "
                   "remnant {:.4f}, clusters {}; record: {}\n",
                   last->time, last->spin / recorder.reference().omegaC, last->shedFraction,
                   last->remnantFraction, last->clusters, piles.pile.file);
    }
    if (ctx.isRoot() && !ctx.options.quiet && !last && code == 0)
        fmt::print("rubble pile: nothing recorded: the run ended before the pile settled "
                   "(pile.settle_steps = {}) and was first recorded\n",
                   piles.pile.settleSteps);
    return code;
}

} // namespace

} // namespace regolith::apps

int main(int argc, char** argv) {
    using namespace regolith;
    return core::runApp(argc, argv, "spin_up", apps::spinUpScene(), apps::runRubblePile);
}
