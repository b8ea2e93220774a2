#include "domain/SfcPartition.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace regolith::domain {

namespace {

/// Moves single elements across the cuts of `owner` while that relieves a part: the boundary
/// element of the heavier of two neighbouring parts goes to the lighter one when the lighter
/// then still weighs less than the heavier did. Each move lowers the sum of squared loads, and
/// neither raises the largest load nor lowers the smallest, so the bound of partitionCurve
/// holds; the moves stop where no single element can move (a local optimum of the cut).
void relieveHeaviest(std::span<double const> weights, int parts, std::vector<int>& owner) {
    auto const P = static_cast<std::size_t>(parts);
    std::vector<std::size_t> begin(P + 1, weights.size()); // part r: [begin[r], begin[r + 1])
    std::vector<double> load(P, 0.0);
    std::size_t i = 0;
    for (std::size_t r = 0; r < P; ++r) { // the first element of owner >= r
        while (i < weights.size() && static_cast<std::size_t>(owner[i]) < r)
            ++i;
        begin[r] = i;
    }
    for (std::size_t k = 0; k < weights.size(); ++k)
        load[static_cast<std::size_t>(owner[k])] += weights[k];
    // Each pass visits every cut; a bound on the passes keeps rounding from cycling.
    for (std::size_t pass = 0; pass < 4 * weights.size() + 4; ++pass) {
        bool moved = false;
        for (std::size_t r = 0; r + 1 < P; ++r) {
            std::size_t const cut = begin[r + 1]; // between parts r and r + 1
            if (load[r] > load[r + 1] && cut > begin[r]) {
                double const w = weights[cut - 1];
                if (w > 0.0 && load[r + 1] + w < load[r]) {
                    load[r] -= w;
                    load[r + 1] += w;
                    begin[r + 1] = cut - 1;
                    moved = true;
                }
            } else if (load[r + 1] > load[r] && cut < begin[r + 2]) {
                double const w = weights[cut];
                if (w > 0.0 && load[r] + w < load[r + 1]) {
                    load[r + 1] -= w;
                    load[r] += w;
                    begin[r + 1] = cut + 1;
                    moved = true;
                }
            }
        }
        if (!moved)
            break;
    }
    for (std::size_t r = 0; r < P; ++r)
        for (std::size_t k = begin[r]; k < begin[r + 1]; ++k)
            owner[k] = static_cast<int>(r);
}

} // namespace

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
    if (!counted)
        relieveHeaviest(weights, parts, owner);
    return owner;
}

} // namespace regolith::domain
