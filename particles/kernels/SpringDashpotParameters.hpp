#pragma once
/// The spring-dashpot batch kernels' view of a pair of materials (SpringDashpotBatch,
/// SpringDashpotWallBatch; the lanes' arithmetic in SpringDashpotLanes.hpp).
#include "particles/kernels/SpringDashpot.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace regolith::particles::spring_lanes {

/// A pair of materials' parameters as the lanes read them; model C's are read only by
/// Rolling::Spring (`spring` 1 where the pair has it, else 0: model A).
struct Parameters {
    double k, kt, ratio, mu, ctRatio, muRoll, spring, kr, etaR;
};

/// Each of N contacts' parameters in lanes of their own (a batch with several materials; with
/// one, the lanes read Parameters as constants).
template <std::size_t N>
struct ParameterLanes {
    using Lane = std::array<double, N>;
    alignas(64) Lane k, kt, ratio, mu, ctRatio, muRoll, spring, kr, etaR;

    void set(std::size_t i, Parameters const& p) {
        k[i] = p.k;
        kt[i] = p.kt;
        ratio[i] = p.ratio;
        mu[i] = p.mu;
        ctRatio[i] = p.ctRatio;
        muRoll[i] = p.muRoll;
        spring[i] = p.spring;
        kr[i] = p.kr;
        etaR[i] = p.etaR;
    }
    [[nodiscard]] Parameters at(std::size_t i) const {
        return {k[i], kt[i], ratio[i], mu[i], ctRatio[i], muRoll[i], spring[i], kr[i], etaR[i]};
    }
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
