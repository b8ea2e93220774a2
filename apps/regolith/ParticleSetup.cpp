#include "apps/regolith/ParticleSetup.hpp"

#include "core/Error.hpp"
#include "core/log/Log.hpp"
#include "particles/integration/TimeStepGuard.hpp"
#include "particles/kernels/HertzMindlin.hpp"
#include "particles/kernels/MaterialMixing.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/simulation/ContactModelRegistry.hpp"
#include "particles/validation/ParticleValidation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <variant>

namespace regolith::apps {

namespace {

particles::ParticleInit particleOf(particles::GrainInit const& g) {
    particles::ParticleInit p;
    p.uid = g.uid;
    p.position = g.position;
    p.velocity = g.velocity;
    p.angularVelocity = g.angularVelocity;
    p.radius = g.radius;
    p.mass = g.mass;
    p.type = g.type;
    p.flags.set(particles::Flag::Fixed, g.fixed);
    return p;
}

[[noreturn]] void notLocal(particles::GrainInit const& g) {
    throw core::Error(fmt::format("grain uid {} at [{}, {}, {}] was generated on a rank that "
                                  "owns no block containing it",
                                  g.uid, g.position.x(), g.position.y(), g.position.z()));
}

} // namespace

void addGeneratedMaster(particles::ParticleStorage& masters, particles::GrainInit const& g,
                        domain::BlockForest const& forest, int rank) {
    domain::Block const* block = forest.localBlockContaining(g.position);
    if (block == nullptr)
        notLocal(g);
    particles::ParticleInit p = particleOf(g);
    p.owner = {rank, block->id.raw()};
    masters.add(p);
}

void addMasters(particles::LocalParticles& local, std::span<particles::GrainInit const> grains) {
    for (auto const& g : grains)
        if (!local.addMaster(particleOf(g)))
            notLocal(g);
}

std::size_t materialTypeCount(SceneDescription const& scene) {
    std::uint32_t maxType = 0;
    for (auto const& spec : scene.particles)
        maxType = std::max(maxType, spec.type);
    for (auto const& wall : scene.walls)
        maxType = std::max(maxType, wall.type);
    for (auto const& insert : scene.inserts)
        maxType = std::max(maxType, insert.type);
    std::size_t const declared = scene.materials.perType ? scene.materials.types.size() : 0;
    return std::max(static_cast<std::size_t>(maxType) + 1, declared);
}

namespace {

/// The largest relative impact speed to expect: twice the fastest grain, or a fall over the
/// domain under external gravity, whichever is larger; 1 when both are zero (a scene at rest
/// has no natural speed, and t_c depends on it only as v^(-1/5)).
double impactVelocityEstimate(core::Comm const& comm, particles::ParticleStorage const& ps,
                              SceneDescription const& scene) {
    double vmax = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i)
        vmax = std::max(vmax, ps.velocity(i).norm());
    vmax = comm.allReduce(vmax, core::ReduceOp::Max);
    double const fall =
        std::sqrt(2.0 * scene.gravity.external.norm() * scene.forest.domain.extent().maxCoeff());
    double const v = std::max(2.0 * vmax, fall);
    return v > 0.0 ? v : 1.0;
}

} // namespace

particles::ContactTimeEstimate contactTime(core::Comm const& comm,
                                           particles::ParticleStorage const& ps,
                                           SceneDescription const& scene) {
    return particles::shortestContactTime(
        comm, makeContactModel(scene).contactTime(ps, impactVelocityEstimate(comm, ps, scene)));
}

particles::AnyContactModel makeContactModel(SceneDescription const& scene) {
    std::vector<particles::MaterialProperties> types(materialTypeCount(scene));
    for (std::uint32_t t = 0; t < types.size(); ++t)
        types[t] = scene.materials.of(t);
    core::ConfigTable const contact =
        scene.contact.table ? *scene.contact.table : core::ConfigTable::fromString("", "");
    particles::ContactModelEntry const* entry =
        particles::contactModels().find(scene.contact.model);
    if (entry == nullptr)
        throw core::InputError("contact.model: no contact model \"" + scene.contact.model +
                               "\" is registered");
    return entry->make({contact, types, scene.contact.rollingSpring});
}

particles::AnyIntegrator makeIntegrator(SceneDescription const& scene) {
    if (scene.time.integrator == Integrator::Euler)
        return particles::SemiImplicitEuler{};
    return particles::VelocityVerlet{.orientation = scene.time.orientation};
}

particles::WallList makeWalls(SceneDescription const& scene) {
    particles::WallList walls;
    for (particles::Wall const& w : scene.walls)
        walls.add(w);
    return walls;
}

namespace {

/// Warns if a periodic length lies below 2 (r_a + r_b) for the two largest grains while the
/// contacts carry springs (friction or rolling friction): a pair may then touch through two
/// periodic images at once, and both contacts share one spring (a grain's contact history is
/// keyed by its partner's uid; docs/notes/contact-models.md, "A pair touching through two periodic
/// images shares one tangential spring"). COLLECTIVE.
void warnTwoImageContacts(core::Comm const& comm, particles::ParticleStorage const& ps,
                          SceneDescription const& scene) {
    auto const springs = [](particles::MaterialProperties const& m) {
        return m.friction > 0.0 || m.rollingFriction > 0.0;
    };
    if (std::none_of(scene.materials.types.begin(), scene.materials.types.end(), springs))
        return;
    double largest = 0.0;
    for (std::size_t k = 0; k < ps.size(); ++k)
        largest = std::max(largest, ps.radius(k));
    double const r1 = comm.allReduce(largest, core::ReduceOp::Max);
    // The second largest: r1 again if two grains have it, else the largest of the others.
    long long atLargest = 0;
    double second = 0.0;
    for (std::size_t k = 0; k < ps.size(); ++k) {
        double const r = ps.radius(k);
        if (r == r1 && atLargest++ == 0)
            continue;
        second = std::max(second, r);
    }
    atLargest = comm.allReduce(atLargest, core::ReduceOp::Sum);
    double const r2 = atLargest >= 2 ? r1 : comm.allReduce(second, core::ReduceOp::Max);
    core::Vec3 const extent = scene.forest.domain.extent();
    for (int a = 0; a < 3; ++a) {
        double const reach = 2.0 * (r1 + r2);
        if (!scene.forest.periodic[static_cast<std::size_t>(a)] || !(extent[a] < reach))
            continue;
        core::log::warn("domain: the periodic length {:g} along {} is below 2 (r_a + r_b) = "
                        "{:g} for the two largest grains (radii {:g} and {:g}): a pair can "
                        "touch through two periodic images at once, and then both contacts share "
                        "one tangential spring (a contact history is keyed by the partner's "
                        "uid), so friction acts on them only approximately and reproducible "
                        "mode is not bitwise the same on every block layout; enlarge the domain "
                        "along {}",
                        extent[a], "xyz"[a], reach, r1, r2, "xyz"[a]);
        return;
    }
}

} // namespace

void checkInitialState(core::Comm const& comm, particles::ParticleStorage const& ps,
                       SceneDescription const& scene) {
    particles::ValidationOptions options;
    options.domain = scene.forest.domain;
    options.periodic = scene.forest.periodic;
    options.overlapTolerance = scene.contact.initialOverlap;
    options.numTypes = materialTypeCount(scene);
    particles::validateParticles(comm, ps, options);
    particles::checkTimeStep(scene.time.dt, contactTime(comm, ps, scene), scene.time.allowUnstable);
    warnTwoImageContacts(comm, ps, scene);
}

void checkOverlapsAcrossBlocks(core::Comm const& comm, particles::LocalParticles const& local,
                               std::span<particles::ContactList const> contacts,
                               double overlapTolerance) {
    // The pair with the smallest (uid_i, uid_j) on this rank, then over all ranks, so the
    // message does not depend on the layout. Each contact is in exactly one block's list.
    using Key = std::pair<particles::Uid, particles::Uid>;
    Key worst{particles::kInvalidUid, particles::kInvalidUid};
    std::string message;
    auto const blocks = local.blocks();
    for (std::size_t b = 0; b < blocks.size() && b < contacts.size(); ++b) {
        particles::ParticleStorage const& ps = blocks[b].particles;
        for (particles::Contact const& c : contacts[b].pairs) {
            if (ps.flags(c.i).isFixed() && ps.flags(c.j).isFixed())
                continue;
            double const rMin = std::min(ps.radius(c.i), ps.radius(c.j));
            Key const key{ps.uid(c.i), ps.uid(c.j)};
            if (!(c.penetration > overlapTolerance * rMin) || !(key < worst))
                continue;
            worst = key;
            // The wording of particles::validateParticles, which finds the same pairs when
            // both grains are on one rank.
            message = particles::initialOverlapMessage(ps, c, overlapTolerance);
        }
    }
    auto const firsts = comm.allGather<std::uint64_t>(worst.first);
    auto const seconds = comm.allGather<std::uint64_t>(worst.second);
    std::size_t reporter = 0;
    for (std::size_t r = 1; r < firsts.size(); ++r)
        if (Key{firsts[r], seconds[r]} < Key{firsts[reporter], seconds[reporter]})
            reporter = r;
    if (firsts[reporter] == particles::kInvalidUid)
        return;
    comm.broadcast(message, static_cast<int>(reporter));
    throw core::InputError(message);
}

} // namespace regolith::apps
