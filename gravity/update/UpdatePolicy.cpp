#include "gravity/update/UpdatePolicy.hpp"

#include "core/Error.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "gravity/common/UidHash.hpp"
#include "gravity/update/GrainRecordExchange.hpp"

#include <fmt/format.h>

#include <algorithm>
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

UpdatePolicy::UpdatePolicy(double threshold, std::array<double, 3> period, UpdateInterval interval)
    : m_threshold(threshold)
    , m_interval(interval)
    , m_every(interval.every)
    , m_period(period) {
    if (!(threshold >= 0.0) || !std::isfinite(threshold))
        throw core::InputError(fmt::format(
            "gravity.update_threshold = {}: the displacement threshold must be finite and "
            ">= 0 m",
            threshold));
    if (interval.every < 0 || (interval.every > 0 && !(interval.dt > 0.0)) ||
        (interval.adaptive && !(interval.budget > 0.0 && interval.budget < 1.0)) ||
        (interval.adaptive && interval.maxEvery < interval.every))
        throw core::InputError(fmt::format(
            "gravity.update_every = {}: expected a number of steps >= 1 (with a time step > 0), "
            "or an adaptive interval with a prediction error in (0, 1)",
            interval.every));
}

UpdatePolicy::~UpdatePolicy() = default;
UpdatePolicy::UpdatePolicy(UpdatePolicy&&) noexcept = default;
UpdatePolicy& UpdatePolicy::operator=(UpdatePolicy&&) noexcept = default;

bool UpdatePolicy::due(core::Comm const& comm, std::span<std::uint64_t const> uid,
                       std::span<double const> x, std::span<double const> y,
                       std::span<double const> z) {
    if (!keepsRecords())
        return true; // every step, on every rank alike: nothing to measure or agree on
    std::array<double, 2> global = localVerdict(uid, x, y, z);
    comm.allReduceInPlace(std::span<double>(global), core::ReduceOp::Max);
    return decideDue(comm, global, uid, x, y, z);
}

std::array<double, 2> UpdatePolicy::localVerdict(std::span<std::uint64_t const> uid,
                                                 std::span<double const> x,
                                                 std::span<double const> y,
                                                 std::span<double const> z) {
    if (!keepsRecords())
        return {0.0, 0.0};
    ++m_call;
    ++m_since;
    double local = m_updates == 0 ? std::numeric_limits<double>::infinity() : 0.0;
    bool const same = std::equal(uid.begin(), uid.end(), m_foundUid.begin(), m_foundUid.end());
    if (!same) {
        m_foundUid.assign(uid.begin(), uid.end());
        m_found.assign(uid.size(), nullptr);
    }
    // The same grains as at the last call, all found then: nothing to look up or measure
    // without a threshold (most steps of an interval).
    bool const lookup = !same || m_threshold > 0.0;
    m_missing.clear(); // grains without a record here: they changed rank
    for (std::size_t i = 0; lookup && i < uid.size() && std::isfinite(local); ++i) {
        if (m_found[i] == nullptr) {
            auto const it = m_records.find(uid[i]);
            if (it == m_records.end()) {
                m_missing.push_back(i);
                continue;
            }
            m_found[i] = &it->second;
        }
        m_found[i]->seen = m_call;
        if (m_threshold > 0.0)
            local =
                std::max(local, distance(m_found[i]->record.reference, x[i], y[i], z[i], m_period));
    }
    m_localMax = local;
    m_lookedUp = lookup;
    return {local, m_missing.empty() ? 0.0 : 1.0};
}

bool UpdatePolicy::decideDue(core::Comm const& comm, std::array<double, 2> global,
                             std::span<std::uint64_t const> uid, std::span<double const> x,
                             std::span<double const> y, std::span<double const> z) {
    if (!keepsRecords())
        return true;
    double local = m_localMax;
    bool const stepsDue = m_every > 0 && m_since >= m_every;
    // Records are fetched unless the step updates anyway (the next due() would give them away);
    // with an interval an update needs them too: the slopes are differences with the old field.
    bool const needed =
        std::isfinite(global[0]) &&
        (m_every > 0 || (!stepsDue && (m_threshold == 0.0 || global[0] <= m_threshold)));
    if (global[1] > 0.0 && needed) {
        // Not due on the grains here, but some arrived: their records decide (all ranks).
        if (!m_exchange)
            m_exchange = std::make_unique<core::SparseExchange>(comm);
        std::vector<std::uint64_t> wanted;
        wanted.reserve(m_missing.size());
        for (std::size_t const i : m_missing)
            wanted.push_back(uid[i]);
        if (!m_lookedUp) // this rank's records are claimed: none is given away
            for (Entry* e : m_found)
                if (e != nullptr)
                    e->seen = m_call;
        fetchMigratedRecords(*m_exchange, comm.size(), m_records, wanted, m_call);
        for (std::size_t const i : m_missing) {
            auto const it = m_records.find(uid[i]);
            if (it != m_records.end())
                m_found[i] = &it->second;
            if (it == m_records.end())
                local = std::numeric_limits<double>::infinity(); // a grain new since the update
            else if (m_threshold > 0.0)
                local = std::max(local,
                                 distance(it->second.record.reference, x[i], y[i], z[i], m_period));
        }
        global[0] = comm.allReduce(local, core::ReduceOp::Max);
    }
    if (m_lookedUp || global[1] > 0.0) { // the fields in grain order, for fieldAt() and fieldsAt()
        m_atField.resize(3 * uid.size());
        m_atSlope.resize(3 * uid.size());
        for (std::size_t i = 0; i < m_found.size(); ++i)
            for (std::size_t a = 0; a < 3 && m_found[i] != nullptr; ++a) {
                m_atField[3 * i + a] = m_found[i]->record.field[a];
                m_atSlope[3 * i + a] = m_found[i]->record.slope[a];
            }
    }
    m_lastMax = global[0];
    return stepsDue || !std::isfinite(m_lastMax) || (m_threshold > 0.0 && m_lastMax > m_threshold);
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
    if (!keepsRecords())
        return; // due() never looks at the records
    std::unordered_map<std::uint64_t, Entry> records;
    records.reserve(uid.size());
    m_judgedUid.clear();
    m_judgedError.clear();
    // The time since the last update: the slopes' denominator, and the prediction's lead.
    double const elapsed = static_cast<double>(m_since) * m_interval.dt;
    for (std::size_t i = 0; i < uid.size(); ++i) {
        Entry e{{{x[i], y[i], z[i]}, {ax[i], ay[i], az[i]}, {}}, m_call};
        auto const old = m_records.find(uid[i]);
        if (m_every > 0 && old != m_records.end() && elapsed > 0.0) {
            GrainRecord const& r = old->second.record;
            double diff = 0.0, norm = 0.0;
            for (std::size_t a = 0; a < 3; ++a) {
                e.record.slope[a] = (e.record.field[a] - r.field[a]) / elapsed;
                double const d = r.field[a] + r.slope[a] * elapsed - e.record.field[a];
                diff += d * d;
                norm += e.record.field[a] * e.record.field[a];
            }
            if (norm > 0.0) {
                m_judgedUid.push_back(uid[i]);
                m_judgedError.push_back(std::sqrt(diff / norm));
            }
        }
        records[uid[i]] = e;
    }
    m_records = std::move(records);
    forgetFound(); // the entries moved
    m_since = 0;
}

void UpdatePolicy::adaptInterval(core::Comm const& comm) {
    if (!m_interval.adaptive)
        return;
    // The sample: the grains whose uid hash a stride picks, the same on any layout.
    auto const judged =
        comm.allReduce(static_cast<unsigned long long>(m_judgedUid.size()), core::ReduceOp::Sum);
    if (judged == 0)
        return; // the first update: nothing predicted yet
    std::uint64_t const stride = std::max<std::uint64_t>(1, judged / m_interval.sample);
    std::vector<double> mine;
    for (std::size_t i = 0; i < m_judgedUid.size(); ++i)
        if (uidHash(m_judgedUid[i]) % stride == 0)
            mine.push_back(m_judgedError[i]);
    std::vector<double> all = comm.allGatherVarying<double>(mine);
    std::sort(all.begin(), all.end()); // the ranks' order differs by layout; the set does not
    if (all.empty())
        return;
    double const e = all[(all.size() - 1) / 2];
    m_lastPredictionError = e;
    // The interval just ended predicted with slopes from the update before it (error ∝
    // interval²) unless that was the first update (kept field: ∝ interval).
    double const power = m_updates > 2 ? 2.0 : 1.0;
    double const scale = e > 0.0 ? std::pow(m_interval.budget / e, 1.0 / power) : 2.0;
    auto const interval = static_cast<double>(m_every);
    m_every = std::clamp(static_cast<long long>(std::floor(interval * std::clamp(scale, 0.5, 2.0))),
                         1LL, m_interval.maxEvery);
}

double UpdatePolicy::sinceUpdateSeconds() const {
    return m_every > 0 ? static_cast<double>(m_since) * m_interval.dt : 0.0;
}

std::array<double, 3> UpdatePolicy::fieldAt(std::size_t i) const {
    double const elapsed = sinceUpdateSeconds();
    double const* f = &m_atField[3 * i];
    double const* s = &m_atSlope[3 * i];
    return {f[0] + s[0] * elapsed, f[1] + s[1] * elapsed, f[2] + s[2] * elapsed};
}

void UpdatePolicy::fieldsAt(std::span<double> x, std::span<double> y, std::span<double> z) const {
    double const elapsed = sinceUpdateSeconds();
    double const* f = m_atField.data();
    double const* s = m_atSlope.data();
    for (std::size_t i = 0; i < x.size(); ++i, f += 3, s += 3) {
        x[i] = f[0] + s[0] * elapsed;
        y[i] = f[1] + s[1] * elapsed;
        z[i] = f[2] + s[2] * elapsed;
    }
}

void UpdatePolicy::restoreInterval(long long sinceUpdate, long long every) {
    m_since = sinceUpdate;
    if (m_interval.adaptive && every > 0)
        m_every = std::min(every, m_interval.maxEvery);
}

GrainRecord const* UpdatePolicy::record(std::uint64_t uid) const {
    auto const it = m_records.find(uid);
    return it == m_records.end() ? nullptr : &it->second.record;
}

void UpdatePolicy::restore(long long updates, std::span<std::uint64_t const> uid,
                           std::span<GrainRecord const> records) {
    m_updates = updates;
    m_records.clear();
    forgetFound();
    if (!keepsRecords())
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
        "gravity.update_threshold = {} exceeds the grain spacing {}: between updates a "
        "neighbour's pull may be off by up to ~2 x threshold / spacing = {:.0f}% (the paper "
        "used twice the largest radius)",
        threshold, spacing, 200.0 * threshold / spacing);
}

} // namespace regolith::gravity
