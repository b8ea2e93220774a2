#include "apps/spin_up/SpinUpTorque.hpp"

namespace regolith::apps {

void addSpinUpTorque(particles::LocalParticles& grains, core::Vec3 const& centre,
                     core::Vec3 const& axis, double alpha, double reach) {
    double const reach2 = reach * reach;
    for (particles::BlockParticles& block : grains.blocks()) {
        particles::ParticleStorage& g = block.particles;
        g.forEachMaster([&](std::size_t i) {
            core::Vec3 const r = g.position(i) - centre;
            if (r.squaredNorm() <= reach2)
                g.force(i) += g.mass(i) * alpha * axis.cross(r);
        });
    }
}

} // namespace regolith::apps
