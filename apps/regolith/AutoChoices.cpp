#include "apps/regolith/AutoChoices.hpp"

#include "apps/regolith/ParticleSetup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

namespace regolith::apps {

namespace {

/// Over all ranks: grain count, smallest radius, largest density.
struct GrainExtremes {
    long long count = 0;
    double minRadius = std::numeric_limits<double>::infinity();
    double maxDensity = 0.0;
};

GrainExtremes extremes(core::Comm const& comm, particles::ParticleStorage const& ps) {
    GrainExtremes e;
    ps.forEachMaster([&](std::size_t i) {
        ++e.count;
        double const r = ps.radius(i);
        e.minRadius = std::min(e.minRadius, r);
        e.maxDensity =
            std::max(e.maxDensity, ps.mass(i) / (4.0 / 3.0 * std::numbers::pi * r * r * r));
    });
    e.count = comm.allReduce(e.count, core::ReduceOp::Sum);
    e.minRadius = comm.allReduce(e.minRadius, core::ReduceOp::Min);
    e.maxDensity = comm.allReduce(e.maxDensity, core::ReduceOp::Max);
    return e;
}

} // namespace

std::vector<AutoChoice> resolveAutoChoices(core::Comm const& comm,
                                           particles::ParticleStorage const& masters,
                                           SceneDescription& scene) {
    std::vector<AutoChoice> out;
    GravitySection& g = scene.gravity;
    if (!(g.self == SelfGravity::Auto || g.thresholdAuto || scene.time.dtAuto))
        return out;
    GrainExtremes const e = extremes(comm, masters);
    if (g.self == SelfGravity::Auto) {
        auto const* point =
            std::find_if(std::begin(kTreeErrors), std::end(kTreeErrors),
                         [&](TreeErrorPoint const& p) { return p.medianError <= g.accuracy; });
        if (e.count <= kDirectSumMaxGrains || point == std::end(kTreeErrors)) {
            g.self = SelfGravity::Direct;
            out.push_back({"gravity.self", "direct",
                           e.count <= kDirectSumMaxGrains
                               ? fmt::format("{} grains: the exact sum is as cheap as the tree "
                                             "up to {}",
                                             e.count, kDirectSumMaxGrains)
                               : fmt::format("accuracy {:g} is finer than the tree's best "
                                             "measured point",
                                             g.accuracy)});
        } else {
            g.self = SelfGravity::Tree;
            g.theta = point->theta;
            out.push_back({"gravity.self", fmt::format("tree, theta = {:g}", point->theta),
                           fmt::format("{} grains; the largest opening angle whose median "
                                       "force error ({:g}) meets accuracy {:g}",
                                       e.count, point->medianError, g.accuracy)});
        }
    }
    if (g.thresholdAuto) {
        g.updateThreshold = g.accuracy * e.minRadius; // accuracy x (2 r_min) / 2
        out.push_back({"gravity.update_threshold", fmt::format("{:.6g}", g.updateThreshold),
                       fmt::format("accuracy {:g} x the smallest grain diameter {:g} / 2",
                                   g.accuracy, 2.0 * e.minRadius)});
    }
    if (scene.time.dtAuto) {
        double const tc = contactTime(comm, masters, scene).contactTime;
        double dt = tc / 20.0;
        std::string reason = fmt::format("contact time {:.6g} / 20", tc);
        if (g.self != SelfGravity::None && e.maxDensity > 0.0) {
            double const orbit =
                2.0 * std::numbers::pi * std::sqrt(3.0 / (std::numbers::pi * g.G * e.maxDensity));
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
        out.push_back({"time.dt", fmt::format("{:.6g}", dt), reason});
    }
    return out;
}

} // namespace regolith::apps
