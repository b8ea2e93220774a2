#include "apps/regolith/InitialState.hpp"

#include "apps/common/AgreeOnInputError.hpp"
#include "apps/regolith/SceneKeyLocation.hpp"
#include "core/Error.hpp"
#include "particles/generators/ParticleGenerator.hpp"

#include <algorithm>

namespace regolith::apps {

std::vector<particles::GrainInit> generateLocalGrains(core::Comm const& comm,
                                                      core::ConfigTable const& sceneRoot,
                                                      SceneDescription const& scene,
                                                      domain::BlockForest const& forest) {
    std::vector<core::AABB> boxes;
    boxes.reserve(forest.blocks().size());
    for (auto const& block : forest.blocks())
        boxes.push_back(block.aabb);
    std::vector<particles::GrainInit> grains;
    // Every rank generates alone (files are read by every rank), so an error may be seen by
    // some ranks only: agree on it before anyone reaches the next collective.
    agreeOnInputError(comm, [&] {
        try {
            grains = particles::generateGrains(scene.particles, forest.domain(), forest.periodic(),
                                               boxes)
                         .grains;
        } catch (core::InputError const& e) {
            throw core::InputError(locateSceneKey(sceneRoot, e.what()));
        }
    });
    return grains;
}

std::vector<MasterRecord> toMasterRecords(std::span<particles::GrainInit const> grains) {
    std::vector<MasterRecord> out;
    out.reserve(grains.size());
    for (auto const& g : grains)
        out.push_back({g.uid, g.position, g.velocity, g.angularVelocity, g.radius, g.mass});
    return out;
}

std::int64_t countWallOverlaps(std::span<MasterRecord const> masters,
                               std::span<particles::Wall const> walls) {
    return std::count_if(masters.begin(), masters.end(), [&](MasterRecord const& m) {
        return std::any_of(walls.begin(), walls.end(), [&](particles::Wall const& w) {
            return w.distance(m.position) < m.radius;
        });
    });
}

} // namespace regolith::apps
