#include "gravity/update/UpdatePolicy.hpp"

#include "core/Error.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "gravity/update/GrainRecordExchange.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <vector>

namespace regolith::gravity {

namespace {

/// b - a to the nearest image where `period` > 0.
double nearest(double b, double a, double period) {
    double const d = b - a;
    return period > 0.0 ? d - period * std::round(d / period) : d;
}

double distance(std::array<double, 3> const& a, double x, double y, double z,
                std::array<double, 3> const& period) {
    double const dx = nearest(x, a[0], period[0]);
    double const dy = nearest(y, a[1], period[1]);
    double const dz = nearest(z, a[2], period[2]);
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

} // namespace

UpdatePolicy::UpdatePolicy(double threshold, std::array<double, 3> period)
    : m_threshold(threshold)
    , m_period(period) {
    if (!(threshold >= 0.0) || !std::isfinite(threshold))
        throw core::InputError(fmt::format(
            "gravity.update_threshold = {}: the displacement threshold must be finite and "
            ">= 0 m",
            threshold));
}

UpdatePolicy::~UpdatePolicy() = default;
UpdatePolicy::UpdatePolicy(UpdatePolicy&&) noexcept = default;
UpdatePolicy& UpdatePolicy::operator=(UpdatePolicy&&) noexcept = default;

bool UpdatePolicy::due(core::Comm const& comm, std::span<std::uint64_t const> uid,
                       std::span<double const> x, std::span<double const> y,
                       std::span<double const> z) {
    if (m_threshold == 0.0)
        return true; // every step, on every rank alike: nothing to measure or agree on
    ++m_call;
    double local = m_updates == 0 ? std::numeric_limits<double>::infinity() : 0.0;
    std::vector<std::size_t> missing; // grains without a record here: they changed rank
    for (std::size_t i = 0; i < uid.size() && std::isfinite(local); ++i) {
        auto const it = m_records.find(uid[i]);
        if (it == m_records.end()) {
            missing.push_back(i);
            continue;
        }
        it->second.seen = m_call;
        local = std::max(local, distance(it->second.record.reference, x[i], y[i], z[i], m_period));
    }
    // One reduction: the largest displacement, and whether any rank misses a record.
    std::array<double, 2> global{local, missing.empty() ? 0.0 : 1.0};
    comm.allReduceInPlace(std::span<double>(global), core::ReduceOp::Max);
    if (global[1] > 0.0 && global[0] <= m_threshold) {
        // Not due on the grains here, but some arrived: their records decide (all ranks).
        if (!m_exchange)
            m_exchange = std::make_unique<core::SparseExchange>(comm);
        std::vector<std::uint64_t> wanted;
        wanted.reserve(missing.size());
        for (std::size_t const i : missing)
            wanted.push_back(uid[i]);
        fetchMigratedRecords(*m_exchange, comm.size(), m_records, wanted, m_call);
        for (std::size_t const i : missing) {
            auto const it = m_records.find(uid[i]);
            local = it == m_records.end()
                        ? std::numeric_limits<double>::infinity() // a grain new since the update
                        : std::max(local, distance(it->second.record.reference, x[i], y[i], z[i],
                                                   m_period));
        }
        global[0] = comm.allReduce(local, core::ReduceOp::Max);
    }
    m_lastMax = global[0];
    return m_lastMax > m_threshold;
}

void UpdatePolicy::markUpdated(std::span<std::uint64_t const> uid, std::span<double const> x,
                               std::span<double const> y, std::span<double const> z) {
    std::vector<double> const zero(uid.size(), 0.0);
    markUpdated(uid, x, y, z, zero, zero, zero);
}

void UpdatePolicy::markUpdated(std::span<std::uint64_t const> uid, std::span<double const> x,
                               std::span<double const> y, std::span<double const> z,
                               std::span<double const> ax, std::span<double const> ay,
                               std::span<double const> az) {
    ++m_updates;
    if (m_threshold == 0.0)
        return; // due() never looks at the records
    m_records.clear();
    m_records.reserve(uid.size());
    for (std::size_t i = 0; i < uid.size(); ++i)
        m_records[uid[i]] = Entry{{{x[i], y[i], z[i]}, {ax[i], ay[i], az[i]}}, m_call};
}

GrainRecord const* UpdatePolicy::record(std::uint64_t uid) const {
    auto const it = m_records.find(uid);
    return it == m_records.end() ? nullptr : &it->second.record;
}

void UpdatePolicy::restore(long long updates, std::span<std::uint64_t const> uid,
                           std::span<GrainRecord const> records) {
    m_updates = updates;
    m_records.clear();
    if (m_threshold == 0.0)
        return;
    for (std::size_t i = 0; i < uid.size(); ++i) {
        auto const& r = records[i].reference;
        if (std::isfinite(r[0]) && std::isfinite(r[1]) && std::isfinite(r[2]))
            m_records[uid[i]] = Entry{records[i], 0}; // NaN: the grain had no record
    }
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
