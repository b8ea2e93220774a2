#include "coupling/gravity/SelfGravityForces.hpp"

#include "coupling/gravity/GravityMethod.hpp"
#include "coupling/gravity/SampledForceError.hpp"
#include "gravity/common/PointMasses.hpp"

#include <algorithm>
#include <array>
#include <numeric>

namespace regolith::coupling {

namespace {

/// The forest's extent on its periodic axes, 0 on the others (UpdatePolicy's `period`).
std::array<double, 3> periodicExtent(domain::BlockForest const& forest) {
    std::array<double, 3> out{};
    for (int a = 0; a < 3; ++a)
        if (forest.periodic()[static_cast<std::size_t>(a)])
            out[static_cast<std::size_t>(a)] = forest.domain().max[a] - forest.domain().min[a];
    return out;
}

} // namespace

SelfGravityForces::SelfGravityForces(core::Comm const& comm, domain::BlockForest const& forest,
                                     SelfGravityConfig const& config)
    : m_comm(&comm)
    , m_config(config)
    , m_method(gravityMethod(config.method).make({comm, forest, m_config}))
    , m_policy(config.updateThreshold, periodicExtent(forest), config.interval)
    , m_monitor(config.check) {}

SelfGravityForces::~SelfGravityForces() = default;

void SelfGravityForces::relocate(domain::BlockForest const& forest) {
    m_method.reset(); // its grid and communicators go before the new ones are made
    m_method = gravityMethod(m_config.method).make({*m_comm, forest, m_config});
    m_gridRefreshed = false;
    m_lastUpdated = false;
}

void SelfGravityForces::gather(particles::LocalParticles const& local, bool state) {
    m_gatheredState = state;
    m_uid.clear();
    m_x.clear();
    m_y.clear();
    m_z.clear();
    m_m.clear();
    m_r.clear();
    for (particles::BlockParticles const& bp : local.blocks()) {
        particles::ParticleStorage const& ps = bp.particles;
        ps.forEachMaster([&](std::size_t i) {
            m_uid.push_back(ps.uid(i));
            if (!state)
                return;
            m_x.push_back(ps.position(i).x());
            m_y.push_back(ps.position(i).y());
            m_z.push_back(ps.position(i).z());
            m_m.push_back(ps.mass(i));
            m_r.push_back(ps.radius(i));
        });
    }
    if (!m_config.reproducible)
        return;
    std::size_t const n = m_uid.size();
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), std::uint32_t{0});
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return m_uid[a] < m_uid[b]; });
    m_slot.resize(n);
    for (std::size_t j = 0; j < n; ++j)
        m_slot[order[j]] = static_cast<std::uint32_t>(j);
    auto permute = [&](auto& v) {
        if (v.empty())
            return;
        auto const copy = v;
        for (std::size_t j = 0; j < n; ++j)
            v[j] = copy[order[j]];
    };
    permute(m_uid);
    permute(m_x);
    permute(m_y);
    permute(m_z);
    permute(m_m);
    permute(m_r);
}

bool SelfGravityForces::needsState() const {
    return m_config.updateThreshold > 0.0 || m_config.interval.every == 0 || m_monitor.armed() ||
           m_policy.stepsSinceUpdate() + 1 >= m_policy.interval();
}

void SelfGravityForces::addForces(particles::LocalParticles& local) {
    gather(local, needsState());
    applyForces(local, m_policy.due(*m_comm, m_uid, m_x, m_y, m_z));
}

std::array<double, 2> SelfGravityForces::voteShare(particles::LocalParticles const& local) {
    gather(local, needsState());
    return m_policy.localVerdict(m_uid, m_x, m_y, m_z);
}

void SelfGravityForces::addForces(particles::LocalParticles& local,
                                  std::array<double, 2> const& vote) {
    applyForces(local, m_policy.decideDue(*m_comm, vote, m_uid, m_x, m_y, m_z));
}

void SelfGravityForces::applyForces(particles::LocalParticles& local, bool updated) {
    std::size_t const n = m_uid.size();
    if (updated && !m_gatheredState) // a grain new since the last update forced it
        gather(local, true);
    m_lastUpdated = updated;
    if (updated && m_monitor.armed() && m_kept.valid) // the step before, now judged
        m_monitor.record(coupling::sampledForceErrors(
            *m_comm, {m_kept.x, m_kept.y, m_kept.z, m_kept.m}, m_kept.uid,
            {m_kept.ax, m_kept.ay, m_kept.az}, m_config.G, m_config.softening, m_monitor.sample()));
    if (updated) {
        m_ax.assign(n, 0.0);
        m_ay.assign(n, 0.0);
        m_az.assign(n, 0.0);
        gravity::PointMasses const grains{m_x, m_y, m_z, m_m, m_r};
        m_stats.potentialEnergy = m_method->evaluate(grains, {m_ax, m_ay, m_az});
        // The policy keeps the field per uid for the steps until the next update.
        m_policy.markUpdated(m_uid, m_x, m_y, m_z, m_ax, m_ay, m_az);
        m_policy.adaptInterval(*m_comm);
        ++m_stats.evaluations;
    }
    // Masters in gather order: index k is the k-th master visited. Between updates the policy
    // guarantees a record for every local master (fetched from the rank it came from).
    if (updated) {
        m_fx = m_ax;
        m_fy = m_ay;
        m_fz = m_az;
    } else {
        m_fx.resize(n);
        m_fy.resize(n);
        m_fz.resize(n);
        m_policy.fieldsAt(m_fx, m_fy, m_fz);
    }
    std::size_t k = 0;
    for (particles::BlockParticles& bp : local.blocks()) {
        particles::ParticleStorage& ps = bp.particles;
        ps.forEachMaster([&](std::size_t i) {
            std::size_t const s = m_config.reproducible ? m_slot[k] : k;
            ps.force(i) += ps.mass(i) * core::Vec3(m_fx[s], m_fy[s], m_fz[s]);
            ++k;
        });
    }
    ++m_stats.steps;
    m_monitor.afterStep(updated, m_stats.evaluations, m_stats.steps);
    if (m_monitor.armed())
        m_kept = {true, m_uid, m_x, m_y, m_z, m_m, m_fx, m_fy, m_fz};
}

SelfGravityState SelfGravityForces::state() const {
    return {m_policy.updates(), m_stats.potentialEnergy, m_policy.stepsSinceUpdate(),
            m_policy.interval()};
}

void SelfGravityForces::restore(SelfGravityState const& state, std::span<particles::Uid const> uid,
                                std::span<gravity::GrainRecord const> records) {
    m_policy.restore(state.updates, uid, records);
    m_policy.restoreInterval(state.sinceUpdate, state.interval);
    m_stats.potentialEnergy = state.potentialEnergy;
}

std::optional<gravity::GridFieldsView> SelfGravityForces::gridFields() const {
    if (m_stats.evaluations == 0 && !m_gridRefreshed)
        return std::nullopt; // zeros: nothing worth writing
    return m_method->gridFields();
}

std::optional<gravity::ErrorStats> SelfGravityForces::sampledForceError(std::size_t sample) const {
    if (!m_lastUpdated)
        return std::nullopt;
    return coupling::sampledForceError(*m_comm, {m_x, m_y, m_z, m_m, m_r}, m_uid,
                                       {m_ax, m_ay, m_az}, m_config.G, m_config.softening, sample);
}

void SelfGravityForces::refreshGridFields(particles::LocalParticles const& local) {
    if (m_stats.evaluations > 0 || m_gridRefreshed || !m_method->gridFields())
        return;
    gather(local, true);
    std::size_t const n = m_uid.size();
    m_ax.assign(n, 0.0);
    m_ay.assign(n, 0.0);
    m_az.assign(n, 0.0);
    (void)m_method->evaluate({m_x, m_y, m_z, m_m, m_r}, {m_ax, m_ay, m_az});
    // The next update solves as it would have without this one (from zero, as after any
    // restart); the forces, the records and the statistics are untouched.
    m_method->resetInitialGuess();
    m_gridRefreshed = true;
}

} // namespace regolith::coupling
