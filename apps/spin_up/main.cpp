// spin_up: a self-gravitating rubble pile spun up to failure ([spin_up]) or passing a point
// mass on a hyperbola ([flyby]), recording its spin, shape, mass shed and largest remnant
// ([pile]) to a CSV file (docs/guide/rubble-piles.md). Runs a scene file (the scene keys of
// `regolith` plus those sections), or scenes/spin-up.toml (compiled in) without one.
// Usage: spin_up --help.
#include "apps/regolith/ParticleSetup.hpp"
#include "apps/regolith/SceneSections.hpp"
#include "apps/spin_up/PileRecorder.hpp"
#include "apps/spin_up/RubblePileSections.hpp"
#include "core/Error.hpp"
#include "core/app/RunApp.hpp"
#include "coupling/simulation/Simulation.hpp"
#include "particles/generators/ParticleGenerator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>

namespace regolith::apps {

std::string_view spinUpScene();

namespace {

/// The scene's run as a coupling::Simulation: the forest, sync, time step, contact law,
/// direct or tree self-gravity and the [[particles]] (no walls, insertion or "auto" keys).
coupling::SimulationSetup simulationSetup(SceneDescription const& scene) {
    if (scene.time.dtAuto || scene.gravity.self == SelfGravity::Auto)
        throw core::InputError("spin_up: time.dt and gravity.self must be given, not \"auto\"");
    if (!scene.walls.empty() || !scene.inserts.empty())
        throw core::InputError("spin_up: a rubble pile has no [[walls]] or [[insert]]");
    coupling::SimulationSetup setup;
    setup.domain = scene.forest;
    setup.sync = scene.sync;
    setup.subdomains = scene.sync.subdomains;
    setup.dem.dt = scene.time.dt;
    setup.contact = makeContactModel(scene);
    if (scene.gravity.self != SelfGravity::None) {
        if (scene.gravity.self != SelfGravity::Direct && scene.gravity.self != SelfGravity::Tree)
            throw core::InputError(
                "gravity.self: spin_up runs \"direct\" or \"tree\" self-gravity");
        coupling::SelfGravityConfig g;
        g.method = scene.gravity.self == SelfGravity::Direct ? coupling::GrainGravityMethod::Direct
                                                             : coupling::GrainGravityMethod::Tree;
        g.G = scene.gravity.G;
        g.softening = scene.gravity.softening;
        g.theta = scene.gravity.theta;
        g.reproducible = scene.sync.reproducible;
        setup.selfGravity = g;
    }
    return setup;
}

int runRubblePile(core::AppContext& ctx) {
    RubblePileScene piles = parseRubblePileScene(ctx.scene); // its keys known before parseScene
    SceneDescription const scene = parseScene(ctx.scene, ctx.options.scenePath);
    std::filesystem::path const file = std::filesystem::path(scene.output.dir) / piles.pile.file;
    std::filesystem::create_directories(file.parent_path());
    piles.pile.file = file.string();

    coupling::Simulation sim(ctx.world, simulationSetup(scene));
    for (particles::GrainInit const& g :
         particles::generateGrains(scene.particles, scene.forest.domain, scene.forest.periodic)
             .grains) {
        particles::ParticleInit p;
        p.uid = g.uid;
        p.position = g.position;
        p.velocity = g.velocity;
        p.angularVelocity = g.angularVelocity;
        p.radius = g.radius;
        p.mass = g.mass;
        p.type = g.type;
        sim.addGrain(p);
    }
    PileRecorder recorder(ctx.world, piles, scene.gravity.G, scene.time.dt);
    sim.addBodyForces([&](particles::LocalParticles& grains) { recorder.addForces(grains); });
    sim.addObserver(recorder.recordEvery(),
                    [&](coupling::Simulation& s) { (void)recorder.record(s.grains()); });
    sim.start();
    sim.run(std::min(piles.pile.settleSteps, scene.time.steps));
    PileReference const& ref = recorder.reference();
    if (ctx.isRoot() && !ctx.options.quiet && ref.mass > 0.0) {
        fmt::print("rubble pile: mass {:.6g}, bulk radius {:.6g}, bulk density {:.6g}, omega_c "
                   "{:.6g} (period {:.6g}), spin {:.3f} omega_c\n",
                   ref.mass, ref.bulkRadius,
                   ref.mass / (4.0 / 3.0 * std::numbers::pi * std::pow(ref.bulkRadius, 3)),
                   ref.omegaC, 2.0 * std::numbers::pi / ref.omegaC, ref.spin / ref.omegaC);
        if (recorder.pass())
            fmt::print("fly-by: the pass takes {:.6g} ({} steps), v_inf {:.6g}\n",
                       recorder.pass()->duration(),
                       static_cast<long long>(recorder.pass()->duration() / scene.time.dt),
                       recorder.pass()->speedAtInfinity());
    }
    sim.run(scene.time.steps - std::min(piles.pile.settleSteps, scene.time.steps));
    std::optional<PileRecord> const end = recorder.record(sim.grains());
    if (ctx.isRoot() && !ctx.options.quiet && end) {
        PileRecord const& last = *end;
        auto const spin = [](std::optional<double> s) {
            return s ? fmt::format("{:.3f} omega_c", *s) : std::string("not reached");
        };
        if (piles.spinUp)
            fmt::print("failure (peak spin): {}; mass shed from: {}\n",
                       spin(recorder.failureSpin()), spin(recorder.sheddingOnset()));
        fmt::print("at t = {:.6g}: spin {:.3f} omega_c, shed {:.4f}, largest remnant {:.4f} "
                   "({} clusters); record: {}\n",
                   last.time, last.spin / ref.omegaC, last.shedFraction, last.remnantFraction,
                   last.clusters, piles.pile.file);
    }
    return 0;
}

} // namespace

} // namespace regolith::apps

int main(int argc, char** argv) {
    using namespace regolith;
    return core::runApp(argc, argv, "spin_up", apps::spinUpScene(), apps::runRubblePile);
}
