#include "particles/simulation/DemStep.hpp"

#include "core/Error.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/simulation/StepAgreement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <utility>

namespace regolith::particles {

DemStep::DemStep(core::Comm const& comm, ParticleSync& sync, LocalParticles& local,
                 AnyContactModel model, AnyIntegrator integrator, WallList walls,
                 DemStepConfig config, core::TimerTree& timers)
    : m_comm(&comm)
    , m_sync(&sync)
    , m_local(&local)
    , m_model(std::move(model))
    , m_integrator(integrator)
    , m_walls(std::move(walls))
    , m_config(config)
    , m_timers(&timers)
    , m_frame(local.forest())
    , m_loop(m_model.blockLoop()) {
    if (!(config.dt > 0.0) || !std::isfinite(config.dt))
        throw core::Error("DemStep: the time step must be positive and finite");
    // A model acting beyond touching: the shadows cover its range (the batch kernels screen
    // overlaps only).
    double const range = m_model.interactionRange();
    if (range > 0.0 && m_model.batched())
        throw core::Error("DemStep: a contact model with a batch kernel must act in overlap only");
    sync.coverReach(range);
    placeOnBlocks();
}

void DemStep::placeOnBlocks() {
    // Per block, the smallest edge of it and its neighbours: a master that moves less in a
    // step stays within the blocks the sync reaches from its block.
    m_reachEdge.clear();
    for (BlockParticles const& bp : m_local->blocks()) {
        double edge = bp.block->aabb.extent().minCoeff();
        for (domain::BlockLink const& l : bp.block->neighbours)
            edge = std::min(edge, l.aabb.extent().minCoeff());
        m_reachEdge.push_back(edge);
    }
    m_movedSinceSync.assign(m_reachEdge.size(), 0.0);
    m_frame = PeriodicFrame(m_local->forest()); // a rebalance may change the wrapped axes
    std::size_t const blocks = m_local->blocks().size();
    // A batch kernel takes springs kept beside the lists (without model C's rolling spring,
    // which stays in the histories).
    DetectorConfig detector = m_config.detector;
    detector.keepSprings = m_config.keepSprings && m_model.batched() && !m_model.hasRollingSpring();
    detector.range = m_model.interactionRange();
    m_detectors.assign(blocks, ContactDetector(detector));
    m_contacts.assign(blocks, ContactList{});
    m_records.assign(blocks, std::vector<ForceRecord>{});
}

int DemStep::relocated() {
    if (m_kickPending)
        throw core::Error("DemStep::relocated: the last step ended Open (its half kick is due)");
    placeOnBlocks();
    return resume(m_steps, time());
}

int DemStep::setUp() {
    m_sync->requireNnsApplicable(*m_local);
    int calls = 0;
    {
        auto const t = m_timers->scope(kSyncTimer);
        // Nothing has moved yet: every master sits in the block that contains it
        // (LocalParticles::addMaster), so no master is transferred or leaves here.
        calls = m_sync->syncUntilConverged(*m_local);
    }
    if (m_config.checkInvariants)
        requireSyncInvariants(*m_local, *m_comm, true, "DemStep set-up", copySkin());
    m_startStep = m_steps;
    computeForces(0);
    m_walls.restartWork();
    writeBackSprings();
    m_moved = 0.0;
    m_kickPending = false;
    return calls;
}

int DemStep::resume(std::uint64_t stepsDone) {
    return resume(stepsDone, static_cast<double>(stepsDone) * m_config.dt);
}

int DemStep::resume(std::uint64_t stepsDone, double time) {
    m_sync->requireNnsApplicable(*m_local);
    int calls = 0;
    {
        auto const t = m_timers->scope(kSyncTimer);
        calls = m_sync->syncUntilConverged(*m_local);
    }
    if (m_config.checkInvariants)
        requireSyncInvariants(*m_local, *m_comm, true, "DemStep resume", copySkin());
    m_steps = stepsDone;
    m_startStep = stepsDone;
    m_startTime = time;
    // The walls' loads stay those of the last evaluation (a relocation keeps them; a restart's
    // fresh walls start from none, so its work counts from the first step's power on).
    m_walls.moveTo(time);
    m_moved = std::numeric_limits<double>::infinity(); // the first detect compares positions
    m_kickPending = false;
    return calls;
}

namespace {

/// postForce, then the next preForce, in one pass where the integrator has one; returns the
/// largest distance a copy moved in both.
template <class I>
double postThenPreForce(I const& integrator, ParticleStorage& ps, double dt, core::Vec3 const& g) {
    if constexpr (requires { integrator.postThenPreForce(ps, dt, g); }) {
        return integrator.postThenPreForce(ps, dt, g);
    } else {
        double const moved = integrator.postForce(ps, dt, g);
        return moved + integrator.preForce(ps, dt, g);
    }
}

/// The largest over the local blocks of what `phase(integrator, storage)` returns (the
/// distance it moved a copy; +inf wins); `relative[b]` grows by block b's share of it over
/// `edges[b]`.
template <class Phase>
double largestOverBlocks(AnyIntegrator const& any, LocalParticles& local,
                         std::span<double const> edges, std::span<double> relative, Phase&& phase) {
    return std::visit(
        [&](auto const& integrator) {
            double moved = 0.0;
            auto const blocks = local.blocks();
            for (std::size_t b = 0; b < blocks.size(); ++b) {
                double const d = phase(integrator, blocks[b].particles);
                relative[b] += d / edges[b];
                moved = std::max(moved, d);
            }
            return moved;
        },
        any);
}

} // namespace

void DemStep::step(StepEnd end) {
    double const dt = m_config.dt;
    core::Vec3 const& g = m_config.gravity;
    {
        auto const t = m_timers->scope(kIntegrateTimer);
        double const moved =
            largestOverBlocks(m_integrator, *m_local, m_reachEdge, m_movedSinceSync,
                              [&](auto const& integrator, ParticleStorage& ps) {
                                  return m_kickPending ? postThenPreForce(integrator, ps, dt, g)
                                                       : integrator.preForce(ps, dt, g);
                              });
        m_moved += moved;
        m_kickPending = false;
    }
    syncParticles();
    ++m_steps;
    computeForces(static_cast<std::uint32_t>(m_steps));
    m_walls.addWork(dt);
    m_kickPending = true;
    if (end == StepEnd::Complete)
        completeStep();
}

void DemStep::completeStep() {
    if (!m_kickPending) {
        writeBackSprings();
        return;
    }
    auto const t = m_timers->scope(kIntegrateTimer);
    writeBackSprings(); // timed with the kick: the pass that makes the grains' state whole
    double const dt = m_config.dt;
    core::Vec3 const& g = m_config.gravity;
    m_moved += largestOverBlocks(m_integrator, *m_local, m_reachEdge, m_movedSinceSync,
                                 [&](auto const& integrator, ParticleStorage& ps) {
                                     return integrator.postForce(ps, dt, g);
                                 });
    m_kickPending = false;
}

double DemStep::copySkin() const {
    return m_sync->config().skin + 0.5 * m_sync->config().reach;
}

std::size_t DemStep::detectorSum(std::size_t DetectorStats::*count) const {
    std::size_t sum = 0;
    for (ContactDetector const& d : m_detectors)
        sum += d.stats().*count;
    return sum;
}

ContactCounts DemStep::contactsOfLastPass() const {
    // computeForces' stamp of the last step; one detector per local block (placeOnBlocks).
    ContactCounts counts = m_local->contactsStamped(static_cast<std::uint32_t>(m_steps));
    for (std::size_t b = 0; b < counts.size(); ++b)
        m_detectors[b].countKeptContacts(counts[b]);
    return counts;
}

void DemStep::writeBackSprings() {
    auto const blocks = m_local->blocks();
    for (std::size_t b = 0; b < blocks.size(); ++b)
        m_detectors[b].writeBackSprings(blocks[b].particles);
}

void DemStep::releaseWorkspace() {
    writeBackSprings();
    for (ContactDetector& d : m_detectors)
        d.release();
    for (ContactList& c : m_contacts)
        c = ContactList{};
    for (auto& r : m_records)
        std::vector<ForceRecord>().swap(r);
}

bool DemStep::agreeAfterSync() {
    bool const quiet = std::exchange(m_listsQuiet, false);
    if (m_comm->size() == 1)
        return m_sync->listHoldsHere(*m_local);
    auto blocks = m_local->blocks();
    AfterSyncAgreement agreed{.bodyForceVote = m_bodyForceVote,
                              .syncListHolds = m_sync->listHoldsHere(*m_local)};
    m_listHalfway.assign(blocks.size(), 0);
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        // In a quiet step no list comes due anywhere, so no list is asked to join a rebuild.
        auto const outlook =
            m_detectors[b].prepareList(blocks[b].particles, blocks[b].block->aabb, m_frame, !quiet);
        agreed.listDue = agreed.listDue || outlook.due;
        m_listHalfway[b] = outlook.halfway ? 1 : 0;
    }
    if (quiet && !m_bodyForceShare) { // StepAgreement.hpp: nothing to agree on
        if (agreed.listDue)
            throw core::Error("DemStep: a Verlet list came due although every copy moved less "
                              "than its quiet motion");
        return true;
    }
    agreed.reduce(*m_comm);
    m_bodyForceVote = agreed.bodyForceVote;
    if (agreed.listDue)
        for (std::size_t b = 0; b < blocks.size(); ++b)
            if (m_listHalfway[b] != 0)
                m_detectors[b].rebuildNext();
    return agreed.syncListHolds;
}

void DemStep::computeForces(std::uint32_t stamp) {
    bool const reproducible = m_sync->config().reproducible;
    bool const keepPairs = m_config.keepContacts || stamp == 0;
    bool syncListHolds = false; // on every rank (agreeAfterSync)
    m_bodyForceVote = {};
    if (m_bodyForceShare) {
        auto const t = m_timers->scope(kBodyForceTimer);
        m_bodyForceVote = m_bodyForceShare(*m_local);
    }
    {
        auto const t = m_timers->scope(kContactTimer);
        auto blocks = m_local->blocks();
        syncListHolds = agreeAfterSync();
        m_walls.moveTo(time());
        m_walls.resetForces();
        double rebuiltSkin = 0.0; // the largest skin of this step's rebuilds
        for (std::size_t b = 0; b < blocks.size(); ++b) {
            ParticleStorage& ps = blocks[b].particles;
            ps.resetForces();
            m_records[b].clear();
            // The block evaluates the pairs whose ownership point lies in its own box
            // (docs/design.md, "The time step": each contact evaluated once). Walls are global:
            // every block tests its copies against all of them, and the detector keeps a
            // sphere-wall contact only for the sphere's master, so it too is evaluated once.
            m_loop->evaluate(BlockPass{ps, m_detectors[b], m_walls, blocks[b].block->aabb, m_frame,
                                       m_contacts[b], m_config.dt, stamp, keepPairs,
                                       reproducible ? &m_records[b] : nullptr});
            // A block without copies "rebuilds" an empty list every call: not counted.
            bool const rebuilt = m_detectors[b].stats().rebuilt && !ps.empty();
            m_listRebuilds += rebuilt ? 1 : 0;
            rebuiltSkin = rebuilt ? std::max(rebuiltSkin, m_detectors[b].listSkin()) : rebuiltSkin;
            m_listShifts += m_detectors[b].stats().shifts;
        }
        m_listSkin = rebuiltSkin > 0.0 ? rebuiltSkin : m_listSkin;
    }
    {
        auto const t = m_timers->scope(kSyncTimer);
        if (reproducible)
            m_sync->reduceForces(*m_local, m_records, stamp);
        else
            m_sync->reduceForces(*m_local, stamp, syncListHolds);
    }
    // After the reduction: in reproducible mode it sums every master's force from zero.
    if (m_bodyForces) {
        auto const t = m_timers->scope(kBodyForceTimer);
        m_bodyForces(*m_local);
    }
}

} // namespace regolith::particles
