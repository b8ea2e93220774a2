#include "apps/regolith/GravitySetup.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

namespace regolith::apps {

std::unique_ptr<coupling::SelfGravityForces> makeSelfGravity(core::Comm const& comm,
                                                             domain::BlockForest const& forest,
                                                             SceneDescription const& scene) {
    GravitySection const& g = scene.gravity;
    coupling::SelfGravityConfig c;
    switch (g.self) {
    case SelfGravity::None:
        return nullptr;
    case SelfGravity::Direct:
        c.method = coupling::GrainGravityMethod::Direct;
        break;
    case SelfGravity::Tree:
        c.method = coupling::GrainGravityMethod::Tree;
        break;
    case SelfGravity::MutualTree:
        c.method = coupling::GrainGravityMethod::MutualTree;
        break;
    default:
        // The grid methods exist in gravity/ but are not coupled to the grains yet.
        throw core::InputError(fmt::format(
            "gravity.self = \"{}\": this method is not coupled to the time step yet; use "
            "\"direct\", \"tree\" or \"mutual-tree\"",
            toString(g.self)));
    }
    c.G = g.G;
    c.softening = g.softening;
    c.theta = g.theta;
    c.allowLargeTheta = g.allowLargeTheta;
    c.updateThreshold = g.updateThreshold;
    return std::make_unique<coupling::SelfGravityForces>(comm, forest, c);
}

} // namespace regolith::apps
