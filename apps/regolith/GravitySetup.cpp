#include "apps/regolith/GravitySetup.hpp"

#include "apps/regolith/AutoChoices.hpp"
#include "apps/regolith/LoopSummary.hpp"
#include "core/Error.hpp"
#include "core/log/Log.hpp"
#include "coupling/gravity/GravityMethod.hpp"
#include "gravity/update/UpdatePolicy.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace regolith::apps {

double extrapolationBudget(double accuracy, double methodError) {
    double const target = kErrorTarget * accuracy;
    double const left =
        target > methodError ? std::sqrt(target * target - methodError * methodError) : 0.0;
    return std::max(left, kMinExtrapolationShare * accuracy);
}

double extrapolationBudget(GravitySection const& g) {
    double methodError = 0.5 * kErrorTarget * g.accuracy;
    if (g.self == "direct") {
        methodError = 0.0;
    } else if (g.self == "tree") {
        // kTreeErrors runs from large to small θ: log-linear between the two around g.theta.
        auto const& t = kTreeErrors;
        std::size_t const n = std::size(t);
        methodError = g.theta >= t[0].theta ? t[0].medianError : t[n - 1].medianError;
        for (std::size_t k = 0; k + 1 < n; ++k)
            if (g.theta <= t[k].theta && g.theta >= t[k + 1].theta) {
                double const w = (g.theta - t[k + 1].theta) / (t[k].theta - t[k + 1].theta);
                methodError = std::exp((1.0 - w) * std::log(t[k + 1].medianError) +
                                       w * std::log(t[k].medianError));
            }
    }
    return extrapolationBudget(g.accuracy, methodError);
}

gravity::UpdateInterval updateInterval(SceneDescription const& scene) {
    GravitySection const& g = scene.gravity;
    gravity::UpdateInterval u;
    u.dt = scene.time.dt;
    if (g.updateEveryAdaptive) {
        u.every = 1; // the first interval: the second update gives the slopes
        u.adaptive = true;
        u.budget = extrapolationBudget(g);
    } else {
        u.every = g.updateEvery;
    }
    return u;
}

coupling::ForceCheckSchedule forceCheckSchedule(SceneDescription const& scene) {
    GravitySection const& g = scene.gravity;
    auto const& periodic = scene.forest.periodic;
    coupling::ForceCheckSchedule s;
    if (periodic[0] || periodic[1] || periodic[2]) {
        // The check's reference is the free-space direct sum, without periodic images.
        if (!g.checkEveryAuto && g.checkEvery > 0)
            throw core::InputError(fmt::format(
                "gravity.check_every = {}: the check compares with the free-space direct sum, "
                "which has no periodic images, but the domain is periodic; use 0 or \"auto\"",
                g.checkEvery));
        return s;
    }
    if (g.checkEveryAuto)
        s.spacingSteps = std::max<std::int64_t>(1, scene.time.steps / kAutoChecksPerRun);
    else
        s.everyUpdates = g.checkEvery;
    return s;
}

std::optional<coupling::SelfGravityConfig> selfGravityConfig(SceneDescription const& scene) {
    GravitySection const& g = scene.gravity;
    if (g.self == "none")
        return std::nullopt;
    if (g.self == "auto") // resolved before (AutoChoices)
        throw core::InputError("gravity.self = \"auto\": not resolved to a method before the run");
    coupling::SelfGravityConfig c;
    c.method = g.self;
    c.options = g.methodOptions;
    c.cellsPerBlock = scene.forest.cellsPerBlock;
    c.petscOptions = g.petscOptions;
    c.poisson = gravity::parsePoissonMethod(g.poisson);
    c.gradientOrder = g.gradientOrder;
    c.p3mCutoffCells = g.p3mCutoff;
    c.gridSpacing = g.gridSpacing;
    c.neighbourhood = g.neighbourhood;
    c.G = g.G;
    c.softening = g.softening;
    c.theta = g.theta;
    c.allowLargeTheta = g.allowLargeTheta;
    c.updateThreshold = g.updateThreshold;
    c.interval = updateInterval(scene);
    c.reproducible = scene.sync.reproducible;
    c.check = forceCheckSchedule(scene);
    return c;
}

std::string measuredErrorWarning(coupling::ForceErrorMonitor const& measured,
                                 SceneDescription const& scene, long long updates,
                                 long long steps) {
    GravitySection const& g = scene.gravity;
    gravity::ErrorStats const& e = measured.stats();
    if (measured.checks() == 0 || !(e.median > kMeasuredErrorTolerance * g.accuracy))
        return {};
    std::string const reuse =
        g.updateEveryAdaptive ? "set gravity.update_every to fewer steps than the adaptive "
                                "interval took"
        : g.updateEvery > 0   ? fmt::format("lower gravity.update_every (now {})", g.updateEvery)
                              : fmt::format("lower gravity.update_threshold (now {:g}) or set it "
                                              "to \"auto\"",
                                            g.updateThreshold);
    std::string const change =
        updates < steps
            ? fmt::format("the field was reused between updates ({} updates in {} steps): {}",
                          updates, steps, reuse)
        : coupling::gravityMethod(g.self).usesTheta
            ? fmt::format("the field was new every step: lower gravity.theta (now {:g})", g.theta)
            : fmt::format("the field was new every step: choose a more accurate gravity.self than "
                          "\"{}\" (or refine its grid)",
                          g.self);
    return fmt::format(
        "gravity.accuracy = {:g}: the measured median force error over the run is "
        "{:.2g} (p99 {:.2g}; {} checks of about {} grains against the direct sum), more "
        "than {:g}x the accuracy; {}, or raise gravity.accuracy",
        g.accuracy, e.median, e.p99, measured.checks(), measured.sample(), kMeasuredErrorTolerance,
        change);
}

void warnSelfGravityParameters(core::Comm const& comm, particles::LocalParticles const& local,
                               SceneDescription const& scene) {
    warnLazyUpdateThreshold(comm, local, scene);
    warnSoftContacts(comm, local, scene);
    warnCoarseOrbitStep(comm, local, scene);
}

void warnLazyUpdateThreshold(core::Comm const& comm, particles::LocalParticles const& local,
                             SceneDescription const& scene) {
    GravitySection const& g = scene.gravity;
    if (g.self == "none" || !(g.updateThreshold > 0.0))
        return;
    double smallest = std::numeric_limits<double>::infinity();
    masterSource(local)([&](MasterRecord const& m) { smallest = std::min(smallest, m.radius); });
    smallest = comm.allReduce(smallest, core::ReduceOp::Min);
    std::string const warning =
        gravity::UpdatePolicy::thresholdWarning(g.updateThreshold, 2.0 * smallest);
    if (!warning.empty())
        core::log::warn("{}", warning);
}

void warnSoftContacts(core::Comm const& comm, particles::LocalParticles const& local,
                      SceneDescription const& scene) {
    if (scene.gravity.self == "none" || scene.contact.elasticity != particles::Elasticity::Linear)
        return;
    double worst = 0.0; // m² / r³
    masterSource(local)([&](MasterRecord const& g) {
        double const m = g.mass, r = g.radius;
        if (r > 0.0 && std::isfinite(m))
            worst = std::max(worst, m * m / (r * r * r));
    });
    worst = comm.allReduce(worst, core::ReduceOp::Max);
    double stiffness = std::numeric_limits<double>::infinity(); // the softest material's
    for (particles::MaterialProperties const& m : scene.materials.types)
        stiffness = std::min(stiffness, m.stiffness);
    double const overlap = scene.gravity.G * worst / (4.0 * stiffness);
    if (overlap > kSoftContactOverlap)
        core::log::warn(
            "contact.stiffness = {:g} is soft for the grains' own gravity: two touching "
            "grains overlap by {:.3g} of their radius at rest under their attraction "
            "alone (G m² / (2r)² / k, for the grains of largest m² / r³), a pile or an "
            "impact more; self-gravity treats overlapping grains as points, so deep "
            "overlaps are not resisted as they should be: raise contact.stiffness "
            "(and lower time.dt with it)",
            stiffness, overlap);
}

void warnCoarseOrbitStep(core::Comm const& comm, particles::LocalParticles const& local,
                         SceneDescription const& scene) {
    if (scene.gravity.self == "none")
        return;
    double density = 0.0;
    masterSource(local)([&](MasterRecord const& m) {
        double const r = m.radius;
        if (r > 0.0)
            density = std::max(density, m.mass / (4.0 / 3.0 * std::numbers::pi * r * r * r));
    });
    density = comm.allReduce(density, core::ReduceOp::Max);
    if (!(density > 0.0))
        return;
    double const orbit = touchingOrbitPeriod(scene.gravity.G, density);
    if (scene.time.dt > orbit / kOrbitSteps)
        core::log::warn("time.dt = {:g} exceeds the orbital period of two touching grains {:.6g} "
                        "(at the largest density, {:.6g}) / {:g}: a close orbit takes fewer "
                        "steps than that and its energy is not kept; reduce time.dt (\"auto\" "
                        "takes the period / 200)",
                        scene.time.dt, orbit, density, kOrbitSteps);
}

} // namespace regolith::apps
