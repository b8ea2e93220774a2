#include "domain/SfcPartition.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace regolith::domain {

std::vector<int> partitionCurve(std::span<double const> weights, int parts) {
    if (parts < 1)
        throw core::InputError(
            fmt::format("block partition: expected at least one rank, got {}", parts));
    double total = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        double const w = weights[i];
        if (!std::isfinite(w) || w < 0.0)
            throw core::InputError(fmt::format(
                "block weights: block {} along the curve has weight {} (expected finite and >= 0)",
                i, w));
        total += w;
    }
    bool const counted = total <= 0.0;
    if (counted)
        total = static_cast<double>(weights.size());

    std::vector<int> owner(weights.size(), 0);
    double const p = static_cast<double>(parts);
    double prefix = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        double const w = counted ? 1.0 : weights[i];
        double const mid = prefix + 0.5 * w;
        auto const r = static_cast<int>(std::floor(mid / total * p));
        owner[i] = std::clamp(r, 0, parts - 1);
        // Rounding must never send a later element to an earlier rank.
        if (i > 0)
            owner[i] = std::max(owner[i], owner[i - 1]);
        prefix += w;
    }
    return owner;
}

} // namespace regolith::domain
