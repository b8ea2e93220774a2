#pragma once
/// The spring-dashpot batch kernels' view of a pair of materials (SpringDashpotBatch,
/// SpringDashpotWallBatch; the lanes' arithmetic in SpringDashpotLanes.hpp).
#include "particles/kernels/SpringDashpot.hpp"

#include <cstdint>

namespace regolith::particles::spring_lanes {

/// A pair of materials' parameters as the lanes read them; model C's are read only by
/// Rolling::Spring (`spring` 1 where the pair has it, else 0: model A).
struct Parameters {
    double k, kt, ratio, mu, ctRatio, muRoll, spring, kr, etaR;
};

/// The parameters of materials (a, b) of `model`.
inline Parameters parametersOf(SpringDashpot const& model, std::uint32_t a, std::uint32_t b) {
    LinearContactParams const& p = model.materials()(a, b);
    return Parameters{p.stiffness,
                      p.tangentialStiffness,
                      model.dampingRatio(a, b),
                      p.friction,
                      p.tangentialDampingRatio,
                      p.rollingFriction,
                      p.rollingSpring.enabled ? 1.0 : 0.0,
                      p.rollingSpring.stiffness,
                      p.rollingSpring.dampingRatio};
}

/// Which rolling resistance the lanes compute: none (every mu_r = 0), model A's couple, or
/// model C's spring where a pair has it and model A's elsewhere.
enum class Rolling { None, Constant, Spring };

} // namespace regolith::particles::spring_lanes
