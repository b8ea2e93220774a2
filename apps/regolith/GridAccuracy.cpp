#include "apps/regolith/GridAccuracy.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace regolith::apps {

std::span<GridErrorPoint const> gridErrorPoints(std::string_view method) {
    if (method == "pm")
        return kMeshErrors;
    if (method == "p3m")
        return kP3mErrors;
    return {};
}

double expectedGridError(std::span<GridErrorPoint const> points, double cellsAcross) {
    auto const along = [cellsAcross](GridErrorPoint const& a, GridErrorPoint const& b) {
        double const f = std::log(cellsAcross / a.cellsAcrossBody) /
                         std::log(b.cellsAcrossBody / a.cellsAcrossBody);
        return a.medianError * std::pow(b.medianError / a.medianError, f);
    };
    if (points.size() < 2 || cellsAcross >= points.back().cellsAcrossBody)
        return points.back().medianError;
    if (cellsAcross <= points.front().cellsAcrossBody)
        return std::max(points.front().medianError * points.front().cellsAcrossBody / cellsAcross,
                        along(points[0], points[1]));
    std::size_t k = 1;
    while (points[k].cellsAcrossBody < cellsAcross)
        ++k;
    return along(points[k - 1], points[k]);
}

void checkGridAccuracy(core::Comm const& comm, particles::ParticleStorage const& masters,
                       SceneDescription const& scene) {
    GravitySection const& g = scene.gravity;
    auto const points = gridErrorPoints(g.self);
    if (points.empty() || !g.accuracyGiven)
        return;
    // The body's largest extent: the bounding box of the grains, over all ranks.
    std::array<double, 6> box{};
    box.fill(-std::numeric_limits<double>::infinity()); // -min (3), max (3)
    masters.forEachMaster([&](std::size_t i) {
        for (int a = 0; a < 3; ++a) {
            auto const ua = static_cast<std::size_t>(a);
            double const x = masters.position(i)[a];
            double const r = masters.radius(i);
            box[ua] = std::max(box[ua], -(x - r));
            box[ua + 3] = std::max(box[ua + 3], x + r);
        }
    });
    comm.allReduceInPlace(std::span<double>(box), core::ReduceOp::Max);
    double extent = 0.0;
    for (std::size_t a = 0; a < 3; ++a)
        extent = std::max(extent, box[a + 3] + box[a]);
    if (!(extent > 0.0) || !std::isfinite(extent))
        return; // no grains: nothing to resolve
    domain::ForestSpec const& f = scene.forest;
    double h = 0.0; // the coarsest cell edge decides
    for (std::size_t a = 0; a < 3; ++a)
        h = std::max(h, f.domain.extent()[static_cast<int>(a)] /
                            (f.rootBlocks[a] * std::max(f.cellsPerBlock[a], 1)));
    double const across = extent / h;
    double const expected = expectedGridError(points, across);
    if (expected <= g.accuracy)
        return;
    std::string const& name = g.self;
    // The measured point that meets the accuracy nearest to this grid (in log cells).
    GridErrorPoint const* meets = nullptr;
    GridErrorPoint const* best = &points.front();
    for (GridErrorPoint const& p : points) {
        if (p.medianError < best->medianError)
            best = &p;
        if (p.medianError <= g.accuracy &&
            (meets == nullptr || std::abs(std::log(p.cellsAcrossBody / across)) <
                                     std::abs(std::log(meets->cellsAcrossBody / across))))
            meets = &p;
    }
    if (meets == nullptr)
        throw core::InputError(fmt::format(
            "gravity.accuracy = {:g}: gravity.self = \"{}\" reached a median force error of {:g} "
            "at best ({:g} cells across the body, measured on the 38,358-grain agglomerate); "
            "ask for a larger gravity.accuracy or use {}\"tree\" or \"direct\"",
            g.accuracy, name, best->medianError, best->cellsAcrossBody,
            g.self == "pm" ? "\"p3m\", " : ""));
    // Cells per block that put meets->cellsAcrossBody cells across the body.
    double const hNeeded = extent / meets->cellsAcrossBody;
    std::array<int, 3> needed{};
    for (std::size_t a = 0; a < 3; ++a)
        needed[a] = static_cast<int>(
            std::ceil(f.domain.extent()[static_cast<int>(a)] / (f.rootBlocks[a] * hNeeded)));
    throw core::InputError(fmt::format(
        "domain.cells_per_block = [{}, {}, {}] is too {} for gravity.accuracy = {:g} with "
        "gravity.self = \"{}\": {:.1f} cells across the body (extent {:g}) give a median force "
        "error of about {:.2g}; {:g} cells across meet it: domain.cells_per_block = [{}, {}, {}] "
        "(measured on the 38,358-grain agglomerate, docs/results.md)",
        f.cellsPerBlock[0], f.cellsPerBlock[1], f.cellsPerBlock[2],
        meets->cellsAcrossBody > across ? "coarse" : "fine", g.accuracy, name, across, extent,
        expected, meets->cellsAcrossBody, needed[0], needed[1], needed[2]));
}

void checkMeasuredGridAccuracy(coupling::SelfGravityForces const& gravity,
                               SceneDescription const& scene) {
    GravitySection const& g = scene.gravity;
    auto const& periodic = scene.forest.periodic;
    if (gridErrorPoints(g.self).empty() || !g.accuracyGiven || periodic[0] || periodic[1] ||
        periodic[2])
        return;
    auto const measured = gravity.sampledForceError(kAccuracySample);
    if (!measured || measured->median <= g.accuracy)
        return;
    throw core::InputError(fmt::format(
        "gravity.accuracy = {:g}: gravity.self = \"{}\" has a median force error of {:.2g} on "
        "this scene's grains at the start (about {} of them against the direct sum); {}, ask "
        "for a larger gravity.accuracy, or use \"tree\" or \"direct\"",
        g.accuracy, g.self, measured->median, kAccuracySample,
        // P3M's error need not fall with finer cells (GridAccuracy.hpp's kP3mErrors).
        g.self == "p3m" ? "raise gravity.p3m_cutoff or change domain.cells_per_block"
                        : "refine domain.cells_per_block"));
}

} // namespace regolith::apps
