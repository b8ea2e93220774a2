#include "gravity/update/UpdatePolicy.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace regolith::gravity {

UpdatePolicy::UpdatePolicy(double threshold)
    : m_threshold(threshold) {
    if (!(threshold >= 0.0) || !std::isfinite(threshold))
        throw core::InputError(fmt::format(
            "gravity.update_threshold = {}: the displacement threshold must be finite and "
            ">= 0 m",
            threshold));
}

bool UpdatePolicy::due(core::Comm const& comm, std::span<std::uint64_t const> uid,
                       std::span<double const> x, std::span<double const> y,
                       std::span<double const> z) {
    if (m_threshold == 0.0)
        return true; // every step, on every rank alike: nothing to measure or agree on
    double local = m_updates == 0 ? std::numeric_limits<double>::infinity() : 0.0;
    for (std::size_t i = 0; i < uid.size() && std::isfinite(local); ++i) {
        auto const it = m_reference.find(uid[i]);
        if (it == m_reference.end()) {
            local = std::numeric_limits<double>::infinity();
            break;
        }
        double const dx = x[i] - it->second[0];
        double const dy = y[i] - it->second[1];
        double const dz = z[i] - it->second[2];
        local = std::max(local, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    m_lastMax = comm.allReduce(local, core::ReduceOp::Max);
    return m_lastMax > m_threshold;
}

void UpdatePolicy::markUpdated(std::span<std::uint64_t const> uid, std::span<double const> x,
                               std::span<double const> y, std::span<double const> z) {
    ++m_updates;
    if (m_threshold == 0.0)
        return; // due() never looks at the reference positions
    m_reference.clear();
    m_reference.reserve(uid.size());
    for (std::size_t i = 0; i < uid.size(); ++i)
        m_reference[uid[i]] = {x[i], y[i], z[i]};
}

std::string UpdatePolicy::thresholdWarning(double threshold, double spacing) {
    if (!(threshold > spacing))
        return {};
    return fmt::format(
        "gravity.update_threshold = {} m exceeds the grain spacing {} m: between updates a "
        "neighbour's pull may be off by up to ~2 x threshold / spacing = {:.0f}% (the paper "
        "used twice the largest radius)",
        threshold, spacing, 200.0 * threshold / spacing);
}

} // namespace regolith::gravity
