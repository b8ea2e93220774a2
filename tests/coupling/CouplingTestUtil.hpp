#pragma once
// Grains for the coupling tests: every rank builds the same global list and keeps, as
// masters, the grains its blocks contain; forces come back per uid on every rank.
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/SelfGravityForces.hpp"
#include "domain/BlockForest.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <mpi.h>

#include <vector>

namespace regolith::coupling::test {

inline core::Comm const& world() {
    static core::Comm const comm(MPI_COMM_WORLD);
    return comm;
}

struct GlobalGrains {
    std::vector<core::Vec3> position;
    std::vector<double> mass, radius;
};

/// This rank's masters of `grains` (uid = index + 1).
inline particles::LocalParticles localMasters(domain::BlockForest const& forest,
                                              GlobalGrains const& grains) {
    particles::LocalParticles local(forest);
    for (std::size_t k = 0; k < grains.position.size(); ++k) {
        particles::ParticleInit p;
        p.uid = static_cast<particles::Uid>(k + 1);
        p.position = grains.position[k];
        p.radius = grains.radius[k];
        p.mass = grains.mass[k];
        (void)local.addMaster(p);
    }
    return local;
}

/// The self-gravity acceleration of every grain (index = uid - 1) by `method`, on every rank,
/// and the potential energy the method reports.
struct GlobalField {
    std::vector<core::Vec3> acceleration;
    double potentialEnergy = 0.0;
};

inline GlobalField selfGravity(domain::BlockForest const& forest, GlobalGrains const& grains,
                               SelfGravityConfig const& config) {
    particles::LocalParticles local = localMasters(forest, grains);
    SelfGravityForces forces(world(), forest, config);
    forces.addForces(local);
    std::vector<double> flat(3 * grains.position.size(), 0.0);
    for (particles::BlockParticles& bp : local.blocks()) {
        particles::ParticleStorage& ps = bp.particles;
        ps.forEachMaster([&](std::size_t i) {
            auto const k = static_cast<std::size_t>(ps.uid(i) - 1);
            for (int a = 0; a < 3; ++a)
                flat[3 * k + static_cast<std::size_t>(a)] = ps.force(i)[a] / ps.mass(i);
        });
    }
    world().allReduceInPlace(std::span<double>(flat), core::ReduceOp::Sum);
    GlobalField out;
    out.potentialEnergy = forces.stats().potentialEnergy;
    for (std::size_t k = 0; k < grains.position.size(); ++k)
        out.acceleration.emplace_back(flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]);
    return out;
}

} // namespace regolith::coupling::test
