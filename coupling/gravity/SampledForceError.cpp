#include "coupling/gravity/SampledForceError.hpp"

#include "gravity/common/UidHash.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace regolith::coupling {

std::vector<double> sampledForceErrors(core::Comm const& comm, gravity::PointMasses const& grains,
                                       std::span<std::uint64_t const> uid,
                                       gravity::AccelView const& field, double G, double softening,
                                       std::size_t sample) {
    std::size_t const n = grains.size();
    auto const total = comm.allReduce(static_cast<unsigned long long>(n), core::ReduceOp::Sum);
    if (total == 0)
        return {};
    std::uint64_t const stride =
        std::max<std::uint64_t>(1, total / std::max<std::size_t>(sample, 1));
    // The sample's uid (two exact halves), position and method field, from every rank.
    constexpr std::size_t kWidth = 8;
    auto const high = [](std::uint64_t u) { return static_cast<double>(u >> 32U); };
    auto const low = [](std::uint64_t u) { return static_cast<double>(u & 0xffffffffULL); };
    std::vector<double> mine;
    for (std::size_t i = 0; i < n; ++i)
        if (gravity::uidHash(uid[i]) % stride == 0)
            mine.insert(mine.end(), {high(uid[i]), low(uid[i]), grains.x[i], grains.y[i],
                                     grains.z[i], field.ax[i], field.ay[i], field.az[i]});
    std::vector<double> const targets = comm.allGatherVarying<double>(mine);
    std::size_t const count = targets.size() / kWidth;
    // Each rank's grains pull every target; summed over ranks.
    std::vector<double> direct(3 * count, 0.0);
    double const eps2 = softening * softening;
    for (std::size_t t = 0; t < count; ++t) {
        double const* p = &targets[kWidth * t];
        double ax = 0.0, ay = 0.0, az = 0.0;
        for (std::size_t j = 0; j < n; ++j) {
            if (high(uid[j]) == p[0] && low(uid[j]) == p[1])
                continue; // itself
            double const dx = grains.x[j] - p[2], dy = grains.y[j] - p[3], dz = grains.z[j] - p[4];
            double const r2 = dx * dx + dy * dy + dz * dz + eps2;
            double const s = G * grains.m[j] / (r2 * std::sqrt(r2));
            ax += s * dx;
            ay += s * dy;
            az += s * dz;
        }
        direct[3 * t] = ax;
        direct[3 * t + 1] = ay;
        direct[3 * t + 2] = az;
    }
    comm.allReduceInPlace(std::span<double>(direct), core::ReduceOp::Sum);
    std::vector<double> errors;
    for (std::size_t t = 0; t < count; ++t) {
        double const* p = &targets[kWidth * t];
        double const ref = std::hypot(direct[3 * t], direct[3 * t + 1], direct[3 * t + 2]);
        double const diff =
            std::hypot(p[5] - direct[3 * t], p[6] - direct[3 * t + 1], p[7] - direct[3 * t + 2]);
        if (ref > 0.0)
            errors.push_back(diff / ref);
    }
    return errors;
}

gravity::ErrorStats sampledForceError(core::Comm const& comm, gravity::PointMasses const& grains,
                                      std::span<std::uint64_t const> uid,
                                      gravity::AccelView const& field, double G, double softening,
                                      std::size_t sample) {
    return gravity::summarizeErrors(
        sampledForceErrors(comm, grains, uid, field, G, softening, sample));
}

} // namespace regolith::coupling
