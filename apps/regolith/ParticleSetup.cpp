#include "apps/regolith/ParticleSetup.hpp"

#include "core/Error.hpp"
#include "particles/integration/TimeStepGuard.hpp"
#include "particles/kernels/HertzMindlin.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/validation/ParticleValidation.hpp"

#include <algorithm>
#include <cmath>

namespace regolith::apps {

particles::ParticleStorage makeMasters(std::span<particles::GrainInit const> grains,
                                       domain::BlockForest const& forest, int rank) {
    particles::ParticleStorage ps;
    for (auto const& g : grains) {
        domain::Block const* block = forest.localBlockContaining(g.position);
        if (block == nullptr)
            throw core::Error("grain uid " + std::to_string(g.uid) +
                              " was generated on a rank that owns no block containing it");
        particles::ParticleInit p;
        p.uid = g.uid;
        p.position = g.position;
        p.velocity = g.velocity;
        p.angularVelocity = g.angularVelocity;
        p.radius = g.radius;
        p.mass = g.mass;
        p.type = g.type;
        p.owner = {rank, block->id.raw()};
        ps.add(p);
    }
    return ps;
}

namespace {

std::size_t materialTypeCount(SceneDescription const& scene) {
    std::uint32_t maxType = 0;
    for (auto const& spec : scene.particles)
        maxType = std::max(maxType, spec.type);
    for (auto const& wall : scene.walls)
        maxType = std::max(maxType, wall.type);
    return static_cast<std::size_t>(maxType) + 1;
}

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

particles::ContactTimeEstimate contactTime(core::Comm const& comm,
                                           particles::ParticleStorage const& ps,
                                           SceneDescription const& scene) {
    ContactSection const& c = scene.contact;
    std::size_t const types = materialTypeCount(scene);
    if (c.model == ContactModel::SpringDashpot) {
        particles::LinearContactParams p;
        p.stiffness = c.stiffness;
        p.tangentialStiffness =
            2.0 / 7.0 * c.stiffness; // keeps normal and tangential periods equal
        p.restitution = c.restitution;
        p.friction = c.friction;
        p.rollingFriction = c.rollingFriction;
        particles::SpringDashpot const model(
            particles::MaterialTable<particles::LinearContactParams>(types, p));
        return particles::shortestContactTime(comm, particles::estimateContactTime(ps, model));
    }
    // Hertz: contact.stiffness is the effective Young's modulus E*; G* follows for a
    // Poisson ratio of 0.3 (G*/E* = (1 - nu) / (2 (2 - nu)) for like materials).
    particles::HertzMindlinParams p;
    p.effectiveYoungsModulus = c.stiffness;
    p.effectiveShearModulus = c.stiffness * 0.7 / 3.4;
    p.restitution = c.restitution;
    p.friction = c.friction;
    p.rollingFriction = c.rollingFriction;
    particles::HertzMindlin const model(
        particles::MaterialTable<particles::HertzMindlinParams>(types, p));
    double const v = impactVelocityEstimate(comm, ps, scene);
    return particles::shortestContactTime(comm, particles::estimateContactTime(ps, model, v));
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
}

} // namespace regolith::apps
