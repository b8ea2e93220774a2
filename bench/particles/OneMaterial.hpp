#pragma once
/// The one-material spring-dashpot of the particle benchmarks: k_t = 2/7 k_n (as the scenes
/// and bench/peers/lammps_compare.py), tangential damping c_t = c_n / 2 (the default).
#include "particles/kernels/SpringDashpot.hpp"

namespace regolith::bench {

inline particles::SpringDashpot oneMaterialSpringDashpot(double stiffness, double restitution,
                                                         double friction) {
    particles::LinearContactParams p;
    p.stiffness = stiffness;
    p.tangentialStiffness = 2.0 / 7.0 * stiffness;
    p.restitution = restitution;
    p.friction = friction;
    return particles::SpringDashpot(particles::MaterialTable<particles::LinearContactParams>(1, p));
}

} // namespace regolith::bench
