#include "particles/kernels/MaterialMixing.hpp"

#include <cmath>

namespace regolith::particles {

double geometricMean(double a, double b) {
    return a == b ? a : std::sqrt(a * b);
}

LinearContactParams mixLinear(MaterialProperties const& a, MaterialProperties const& b,
                              RollingSpring const& rolling) {
    LinearContactParams p;
    p.stiffness = geometricMean(a.stiffness, b.stiffness);
    p.tangentialStiffness = 2.0 / 7.0 * p.stiffness;
    p.restitution = geometricMean(a.restitution, b.restitution);
    p.friction = geometricMean(a.friction, b.friction);
    p.rollingFriction = geometricMean(a.rollingFriction, b.rollingFriction);
    p.rollingSpring = rolling;
    return p;
}

HertzMindlinParams mixHertz(MaterialProperties const& a, MaterialProperties const& b,
                            RollingSpring const& rolling) {
    HertzMindlinParams p = HertzMindlinParams::fromMaterials(
        a.youngsModulus, a.poissonRatio, b.youngsModulus, b.poissonRatio,
        geometricMean(a.restitution, b.restitution), geometricMean(a.friction, b.friction),
        geometricMean(a.rollingFriction, b.rollingFriction));
    p.rollingSpring = rolling;
    return p;
}

} // namespace regolith::particles
