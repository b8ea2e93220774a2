#include "apps/regolith/InitialState.hpp"

#include "apps/regolith/ParticleSetup.hpp"
#include "apps/regolith/SceneKeyLocation.hpp"
#include "core/Error.hpp"
#include "core/mpi/AgreeOnInputError.hpp"
#include "particles/generators/ParticleGenerator.hpp"

#include <algorithm>

namespace regolith::apps {

void generateLocalGrains(core::Comm const& comm, core::ConfigTable const& sceneRoot,
                         SceneDescription const& scene, domain::BlockForest const& forest,
                         particles::GrainSink const& sink) {
    std::vector<core::AABB> boxes;
    boxes.reserve(forest.blocks().size());
    for (auto const& block : forest.blocks())
        boxes.push_back(block.aabb);
    // Every rank generates alone (files are read by every rank), so an error may be seen by
    // some ranks only: agree on it before anyone reaches the next collective.
    core::agreeOnInputError(comm, [&] {
        try {
            (void)particles::generateGrains(scene.particles, forest.domain(), forest.periodic(),
                                            boxes, sink);
        } catch (core::InputError const& e) {
            throw core::InputError(locateSceneKey(sceneRoot, e.what()));
        }
    });
}

std::vector<particles::GrainInit> generateLocalGrains(core::Comm const& comm,
                                                      core::ConfigTable const& sceneRoot,
                                                      SceneDescription const& scene,
                                                      domain::BlockForest const& forest) {
    std::vector<particles::GrainInit> grains;
    generateLocalGrains(comm, sceneRoot, scene, forest,
                        [&](particles::GrainInit const& g) { grains.push_back(g); });
    return grains;
}

particles::ParticleStorage generateLocalMasters(core::Comm const& comm,
                                                core::ConfigTable const& sceneRoot,
                                                SceneDescription const& scene,
                                                domain::BlockForest const& forest) {
    std::size_t count = 0;
    generateLocalGrains(comm, sceneRoot, scene, forest,
                        [&](particles::GrainInit const&) { ++count; });
    particles::ParticleStorage masters;
    masters.reserve(count);
    int const rank = comm.rank();
    generateLocalGrains(comm, sceneRoot, scene, forest, [&](particles::GrainInit const& g) {
        addGeneratedMaster(masters, g, forest, rank);
    });
    if (masters.size() != count) // the generation is deterministic: never
        throw core::Error("generateLocalMasters: the two generation passes disagree");
    return masters;
}

std::vector<MasterRecord> toMasterRecords(std::span<particles::GrainInit const> grains) {
    std::vector<MasterRecord> out;
    out.reserve(grains.size());
    for (auto const& g : grains) {
        MasterRecord& m = out.emplace_back();
        m.uid = g.uid;
        m.position = g.position;
        m.velocity = g.velocity;
        m.angularVelocity = g.angularVelocity;
        m.radius = g.radius;
        m.mass = g.mass;
    }
    return out;
}

std::int64_t countWallOverlaps(MasterSource const& masters,
                               std::span<particles::Wall const> walls) {
    std::int64_t n = 0;
    if (walls.empty())
        return n;
    masters([&](MasterRecord const& m) {
        n +=
            std::any_of(walls.begin(), walls.end(),
                        [&](particles::Wall const& w) { return w.distance(m.position) < m.radius; })
                ? 1
                : 0;
    });
    return n;
}

} // namespace regolith::apps
