// Tutorial 05: an app on the scene driver.
//
// The `regolith` driver's whole run (scene file, --set, checkpoints and --restart, VTK, the run
// summary) with a force and an observer of one's own added through apps::SceneHooks: a linear
// drag F = -gamma m v on every grain of a granular gas, and the kinetic energy printed every
// 100 steps. The drag alone takes the energy down as exp(-2 gamma t); the inelastic collisions
// only add to the loss, so the program fails if the energy ends above that bound.
// Run: mpiexec -n 2 ./05-scene-app [scene.toml] [--set time.steps=2000] [--output dir] ...
#include "apps/regolith/SceneRun.hpp"
#include "core/app/RunApp.hpp"
#include "coupling/simulation/Simulation.hpp"

#include <cmath>
#include <cstdio>
#include <string_view>

using namespace regolith;

namespace {

// The scene run when no file is given: 512 grains on a periodic 10^3 box, random velocities.
constexpr std::string_view kScene = R"toml(
name = "drag-gas"

[domain]
min = [0.0, 0.0, 0.0]
max = [10.0, 10.0, 10.0]
periodic = [true, true, true]

[time]
dt = 0.005
steps = 1000

[contact]
stiffness = 500.0
restitution = 0.8
friction = 0.3

[[particles]]
kind = "lattice"
lattice = "sc"
spacing = 1.25
radius = 0.4
density = 1.0
velocity = { random = [-1.0, 1.0], seed = 5 }
)toml";

constexpr double kGamma = 0.5; // the drag rate [1/time]

/// The translational kinetic energy of all grains on all ranks. COLLECTIVE.
double kineticEnergy(coupling::Simulation& sim) {
    double e = 0.0;
    sim.forEachGrain([&](particles::ParticleStorage const& g, std::size_t i) {
        e += 0.5 * g.mass(i) * g.velocity(i).squaredNorm();
    });
    return sim.comm().allReduce(e, core::ReduceOp::Sum);
}

} // namespace

int main(int argc, char** argv) {
    apps::SceneHooks hooks;
    // Added to the contact forces in every force computation, on each rank's own grains.
    hooks.bodyForces.push_back([](particles::LocalParticles& local) {
        for (particles::BlockParticles& b : local.blocks())
            b.particles.forEachMaster([&](std::size_t i) {
                b.particles.force(i) -= kGamma * b.particles.mass(i) * b.particles.velocity(i);
            });
    });
    double firstTime = -1.0, firstEnergy = 0.0, lastTime = 0.0, lastEnergy = 0.0;
    // Called after every 100th step, after the scene's own outputs.
    hooks.observers.push_back({100, [&](coupling::Simulation& s) {
                                   double const e = kineticEnergy(s);
                                   if (firstTime < 0.0) {
                                       firstTime = s.time();
                                       firstEnergy = e;
                                   }
                                   lastTime = s.time();
                                   lastEnergy = e;
                                   if (s.comm().rank() == 0)
                                       std::printf("step %lld  t %.3f  kinetic energy %.6g\n",
                                                   static_cast<long long>(s.stepsDone()), s.time(),
                                                   e);
                               }});
    return core::runApp(argc, argv, "05-scene-app", kScene, [&](core::AppContext& ctx) {
        int const code = apps::runSceneWith(ctx, hooks);
        if (code != 0 || firstTime < 0.0)
            return code;
        // The drag's bound, with 1 % for the time step's error.
        double const bound = firstEnergy * std::exp(-2.0 * kGamma * (lastTime - firstTime));
        if (ctx.isRoot())
            std::printf("energy %.6g at t = %.3f; drag alone: at most %.6g\n", lastEnergy, lastTime,
                        bound);
        return lastEnergy <= 1.01 * bound ? 0 : 1;
    });
}
