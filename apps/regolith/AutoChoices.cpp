#include "apps/regolith/AutoChoices.hpp"

#include "apps/regolith/GravitySetup.hpp"
#include "apps/regolith/GridAccuracy.hpp"
#include "apps/regolith/ParticleSetup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>

namespace regolith::apps {

namespace {

/// Over all ranks: grain count, smallest radius, largest density.
struct GrainExtremes {
    long long count = 0;
    double minRadius = std::numeric_limits<double>::infinity();
    double maxDensity = 0.0;
    double extent = 0.0; ///< largest extent of the grains' bounding box (radii included)
};

GrainExtremes extremes(core::Comm const& comm, particles::ParticleStorage const& ps) {
    GrainExtremes e;
    std::array<double, 6> box{}; // -min (3), max (3)
    box.fill(-std::numeric_limits<double>::infinity());
    ps.forEachMaster([&](std::size_t i) {
        for (int a = 0; a < 3; ++a) {
            auto const ua = static_cast<std::size_t>(a);
            box[ua] = std::max(box[ua], ps.radius(i) - ps.position(i)[a]);
            box[ua + 3] = std::max(box[ua + 3], ps.position(i)[a] + ps.radius(i));
        }
        ++e.count;
        double const r = ps.radius(i);
        e.minRadius = std::min(e.minRadius, r);
        e.maxDensity =
            std::max(e.maxDensity, ps.mass(i) / (4.0 / 3.0 * std::numbers::pi * r * r * r));
    });
    e.count = comm.allReduce(e.count, core::ReduceOp::Sum);
    e.minRadius = comm.allReduce(e.minRadius, core::ReduceOp::Min);
    e.maxDensity = comm.allReduce(e.maxDensity, core::ReduceOp::Max);
    comm.allReduceInPlace(std::span<double>(box), core::ReduceOp::Max);
    for (std::size_t a = 0; a < 3; ++a)
        e.extent = std::max(e.extent, box[a + 3] + box[a]);
    return e;
}

/// P3M's measured median error on the scene's grid, or nothing where P3M is not safe: no
/// grid, a refined forest, or mixed periodicity (see kP3mSecondsPerGrain).
std::optional<double> p3mExpectedError(SceneDescription const& scene, GrainExtremes const& e) {
    domain::ForestSpec const& f = scene.forest;
    bool const grid = f.cellsPerBlock[0] > 0 && f.cellsPerBlock[1] > 0 && f.cellsPerBlock[2] > 0;
    bool const periodicAll = f.periodic[0] && f.periodic[1] && f.periodic[2];
    bool const periodicNone = !f.periodic[0] && !f.periodic[1] && !f.periodic[2];
    if (!grid || !f.refine.empty() || !(periodicAll || periodicNone) || !(e.extent > 0.0))
        return std::nullopt;
    double h = 0.0;
    for (std::size_t a = 0; a < 3; ++a)
        h = std::max(h, f.domain.extent()[static_cast<int>(a)] /
                            (f.rootBlocks[a] * f.cellsPerBlock[a]));
    return expectedGridError(kP3mErrors, e.extent / h);
}

} // namespace

double treeCostPerStep(TreeErrorPoint const& p, double accuracy) {
    if (!(p.medianError < kErrorTarget * accuracy))
        return std::numeric_limits<double>::infinity();
    return p.wallMs / std::sqrt(extrapolationBudget(accuracy, p.medianError));
}

std::vector<AutoChoice> resolveAutoChoices(core::Comm const& comm,
                                           particles::ParticleStorage const& masters,
                                           SceneDescription& scene) {
    std::vector<AutoChoice> out;
    GravitySection& g = scene.gravity;
    if (!(g.self == "auto" || g.thresholdAuto || scene.time.dtAuto))
        return out;
    GrainExtremes const e = extremes(comm, masters);
    auto const& periodic = scene.forest.periodic;
    if (g.self == "auto" && (periodic[0] || periodic[1] || periodic[2])) {
        // Only the grid methods are periodic (SceneSections: requireGravityMatchesPeriodicity).
        auto const p3m = p3mExpectedError(scene, e);
        if (g.poisson == "fft")
            throw core::InputError(
                "gravity.self = \"auto\": the domain is periodic, where only the grid methods "
                "apply, and gravity.poisson = \"fft\" is the free-space solver; set "
                "gravity.poisson = \"petsc\"");
        if (!p3m)
            throw core::InputError(
                "gravity.self = \"auto\": the domain is periodic, and only the grid methods (pm, "
                "p3m) have periodic images; they need every axis periodic, domain.cells_per_block "
                "and no refinement: give those, an open domain, or gravity.self");
        g.self = "p3m";
        out.push_back(
            {"gravity.self", "p3m",
             fmt::format("{} grains in a periodic domain, where only the grid methods "
                         "apply; its measured median force error on this grid ({:.2g}) "
                         "{} accuracy {:g}",
                         e.count, *p3m, *p3m <= g.accuracy ? "meets" : "misses", g.accuracy)});
    }
    if (g.self == "auto") {
        auto const* point = std::min_element(std::begin(kTreeErrors), std::end(kTreeErrors),
                                             [&](TreeErrorPoint const& a, TreeErrorPoint const& b) {
                                                 return treeCostPerStep(a, g.accuracy) <
                                                        treeCostPerStep(b, g.accuracy);
                                             });
        if (!std::isfinite(treeCostPerStep(*point, g.accuracy)))
            point = std::end(kTreeErrors);
        if (e.count <= kDirectSumMaxGrains || point == std::end(kTreeErrors)) {
            g.self = "direct";
            out.push_back({"gravity.self", "direct",
                           e.count <= kDirectSumMaxGrains
                               ? fmt::format("{} grains: the exact sum is as cheap as the tree "
                                             "up to {}",
                                             e.count, kDirectSumMaxGrains)
                               : fmt::format("accuracy {:g} is finer than the tree's best "
                                             "measured point",
                                             g.accuracy)});
        } else if (auto const p3m = p3mExpectedError(scene, e);
                   p3m && *p3m <= g.accuracy && kP3mSecondsPerGrain < kTreeSecondsPerGrain) {
            g.self = "p3m";
            out.push_back({"gravity.self", "p3m",
                           fmt::format("{} grains; its measured median force error on this grid "
                                       "({:.2g}) meets accuracy {:g} and it is cheaper than the "
                                       "tree",
                                       e.count, *p3m, g.accuracy)});
        } else {
            g.self = "tree";
            g.theta = point->theta;
            std::string reason = fmt::format(
                "{} grains; with the update interval, the least cost per step: its median force "
                "error ({:g}) leaves {:.2g} to the extrapolation between updates (the run aimed "
                "at {:g} x accuracy {:g})",
                e.count, point->medianError, extrapolationBudget(g.accuracy, point->medianError),
                kErrorTarget, g.accuracy);
            if (p3m && *p3m <= g.accuracy)
                reason += fmt::format("; p3m would meet it on this grid ({:.2g}) but costs {:.0f}x "
                                      "the tree per grain (measured)",
                                      *p3m, kP3mSecondsPerGrain / kTreeSecondsPerGrain);
            // Two keys, each a value --set takes (a restart reuses them: Checkpointing.hpp).
            out.push_back({"gravity.self", "tree", reason});
            out.push_back({"gravity.theta", fmt::format("{}", point->theta),
                           "the opening angle of the least cost per step for gravity.accuracy "
                           "(above)"});
        }
    }
    if (g.thresholdAuto) {
        // The step count decides, the field extrapolated between updates (measured on the
        // default scene, docs/notes/update-interval.md: a displacement threshold updated at
        // nearly every step where bodies move as a whole).
        g.updateThreshold = 0.0;
        bool const given = g.updateEvery > 0 || g.updateEveryAdaptive;
        out.push_back({"gravity.update_threshold", "0",
                       "no displacement limit: gravity.update_every decides"});
        if (!given) {
            g.updateEveryAdaptive = true;
            out.push_back({"gravity.update_every", "adaptive",
                           fmt::format("the field extrapolated in time from the last two updates; "
                                       "the interval follows the extrapolation's measured median "
                                       "error, aimed at {:.2g}",
                                       extrapolationBudget(g))});
        }
    }
    if (scene.time.dtAuto) {
        double const tc = contactTime(comm, masters, scene).contactTime;
        double dt = tc / 20.0;
        std::string reason = fmt::format("contact time {:.6g} / 20", tc);
        if (g.self != "none" && e.maxDensity > 0.0) {
            double const orbit = touchingOrbitPeriod(g.G, e.maxDensity);
            if (orbit / 200.0 < dt) {
                dt = orbit / 200.0;
                reason = fmt::format("orbital period of two touching grains {:.6g} / 200 (below "
                                     "the contact time {:.6g} / 20)",
                                     orbit, tc);
            } else {
                reason += fmt::format(" (below the orbital period {:.6g} / 200)", orbit);
            }
        }
        if (!std::isfinite(dt))
            throw core::InputError("time.dt = \"auto\": no contact and no self-gravity to "
                                   "derive a time step from; give time.dt a value");
        scene.time.dt = dt;
        scene.time.dtAuto = false;
        out.push_back({"time.dt", fmt::format("{}", dt), reason});
    }
    return out;
}

} // namespace regolith::apps
