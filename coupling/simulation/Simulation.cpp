#include "coupling/simulation/Simulation.hpp"

#include "core/Error.hpp"
#include "coupling/balance/BlockWeights.hpp"
#include "coupling/gravity/GravityMethod.hpp"
#include "particles/integration/TimeStepGuard.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <variant>

namespace regolith::coupling {

namespace {

bool usesGrid(std::optional<SelfGravityConfig> const& gravity) {
    return gravity && gravityMethod(gravity->method).usesGrid;
}

/// What the scene driver checks as it reads the gravity section, for a program that sets
/// the self-gravity itself: a Plummer length only for a method that softens, and in a
/// periodic domain only a method with periodic images (a free-space sum would pull grains
/// across a periodic face apart through the whole domain).
void requireGravityFitsTheDomain(SelfGravityConfig const& g, std::array<bool, 3> const& periodic) {
    GravityMethodEntry const& method = gravityMethod(g.method);
    if (g.softening > 0.0 && !method.softens)
        throw core::InputError(
            fmt::format("Simulation: self-gravity method \"{}\" does not soften, but "
                        "SelfGravityConfig::softening = {:g}: use a method that softens, or 0",
                        g.method, g.softening));
    std::string axes;
    for (std::size_t a = 0; a < 3; ++a)
        if (periodic[a])
            axes += std::string(axes.empty() ? "" : ", ") + "xyz"[a];
    if (!axes.empty() && !method.periodic)
        throw core::InputError(fmt::format(
            "Simulation: self-gravity method \"{}\" sums in free space, without periodic "
            "images, but SimulationSetup::domain.periodic makes {} periodic: use a method with "
            "periodic images (a grid method), or an open domain",
            g.method, axes));
}

} // namespace

Simulation::Simulation(core::Comm const& comm, SimulationSetup setup)
    : m_comm(&comm)
    , m_setup(std::move(setup))
    , m_timers([] { return MPI_Wtime(); }) {
    if (!m_setup.contact)
        throw core::InputError("Simulation: no contact model (SimulationSetup::contact)");
    if (!(m_setup.dem.dt > 0.0))
        throw core::InputError(fmt::format(
            "Simulation: time step {}: expected dt > 0 (SimulationSetup::dem.dt)", m_setup.dem.dt));
    if (m_setup.selfGravity)
        requireGravityFitsTheDomain(*m_setup.selfGravity, m_setup.domain.periodic);
    if (usesGrid(m_setup.selfGravity))
        m_setup.domain.cellsPerBlock = m_setup.selfGravity->cellsPerBlock;
}

Simulation::Simulation(core::Comm const& comm, SimulationSetup setup, Placement placed)
    : Simulation(comm, std::move(setup)) {
    m_placed = std::move(placed);
    m_placedByCaller = true;
}

Simulation::~Simulation() = default;

void Simulation::addGrain(particles::ParticleInit const& grain) {
    if (m_dem || m_placedByCaller)
        throw core::Error("Simulation::addGrain after start() or with a Placement");
    m_pending.push_back(grain);
}

void Simulation::addBodyForces(BodyForces forces) {
    m_bodyForces.push_back(std::move(forces));
}

void Simulation::addObserver(std::int64_t every, Observer observer) {
    if (every < 1)
        throw core::InputError(
            fmt::format("Simulation::addObserver: every {}: expected >= 1", every));
    addObserver([every](std::int64_t step) { return step % every == 0; }, std::move(observer), {});
}

void Simulation::addObserver(Due due, Observer observer, ObserverNeeds needs) {
    m_observers.push_back({std::move(due), std::move(observer), needs});
}

void Simulation::place(domain::BlockWeight const& weight) {
    m_placed = placeBlocks(*m_comm, m_setup.domain, weight, m_setup.subdomains);
    for (particles::ParticleInit const& p : m_pending)
        (void)m_placed.local->addMaster(p); // false: another rank's
}

void Simulation::checkTimeStep() const {
    particles::ContactTimeEstimate shortest;
    for (particles::BlockParticles const& block : m_placed.local->blocks()) {
        // Hertz-Mindlin's contact time needs an impact speed: not guarded here (speed 0).
        particles::ContactTimeEstimate const e = m_setup.contact->contactTime(block.particles, 0.0);
        if (e.contactTime < shortest.contactTime)
            shortest = e;
    }
    shortest = particles::shortestContactTime(*m_comm, shortest);
    particles::checkTimeStep(m_setup.dem.dt, shortest, m_setup.allowUnstable);
}

namespace {

/// The sum of each given grain's FNV-1a hash over its state: equal on every rank iff every rank
/// was given the same grains, in any order (up to a collision of about 2^-64).
std::uint64_t digestOf(std::vector<particles::ParticleInit> const& grains) {
    std::uint64_t sum = 0, h = 0;
    auto mix = [&h](auto const& value) {
        auto const* bytes = reinterpret_cast<unsigned char const*>(&value);
        for (std::size_t k = 0; k < sizeof(value); ++k)
            h = (h ^ bytes[k]) * 0x100000001b3ULL;
    };
    auto vec = [&mix](core::Vec3 const& v) {
        for (int a = 0; a < 3; ++a)
            mix(v[a]);
    };
    for (particles::ParticleInit const& g : grains) {
        h = 0xcbf29ce484222325ULL;
        mix(g.uid);
        vec(g.position);
        vec(g.velocity);
        vec(g.angularVelocity);
        vec(g.orientation.vec());
        mix(g.orientation.w());
        mix(g.radius);
        mix(g.mass);
        mix(g.type);
        mix(g.flags.bits());
        for (double f : g.fields)
            mix(f);
        sum += h;
    }
    return sum;
}

} // namespace

void Simulation::start() {
    if (m_dem)
        throw core::Error("Simulation::start or resume called twice");
    if (!m_placedByCaller) {
        // Every rank was given the same grains: each keeps its own, and together they keep all.
        auto const given = static_cast<long long>(m_pending.size());
        if (m_comm->allReduce(given, core::ReduceOp::Min) !=
            m_comm->allReduce(given, core::ReduceOp::Max))
            throw core::InputError("Simulation::start: the ranks were given different numbers "
                                   "of grains (addGrain: every rank gives every grain)");
        auto const digest = static_cast<unsigned long long>(digestOf(m_pending));
        if (m_comm->allReduce(digest, core::ReduceOp::Min) !=
            m_comm->allReduce(digest, core::ReduceOp::Max))
            throw core::InputError("Simulation::start: the ranks were given different grains "
                                   "(addGrain: every rank gives every grain, the same bits; a "
                                   "random start needs the same seed on every rank)");
        place({});
        BlockLoadModel load;
        if (usesGrid(m_setup.selfGravity))
            load = {m_setup.domain.cellsPerBlock, m_setup.domain.cellWeight};
        place(grainAndCellWeights(*m_comm, *m_placed.local, m_placed.local->contactsStamped(0),
                                  load,
                                  m_setup.domain)); // the grains' load
        m_pending.clear();
        m_pending.shrink_to_fit();
        auto const kept = m_comm->allReduce(static_cast<long long>(m_placed.local->countMasters()),
                                            core::ReduceOp::Sum);
        if (kept != given)
            throw core::InputError(fmt::format("Simulation::start: {} of {} grains lie outside "
                                               "the domain or were given twice",
                                               given - kept, given));
        checkTimeStep();
    }
    assemble();
    m_dem->setUp();
    m_steps = 0;
}

void Simulation::resume(std::int64_t stepsDone, double time) {
    if (m_dem)
        throw core::Error("Simulation::start or resume called twice");
    if (!m_placedByCaller)
        throw core::Error("Simulation::resume: the restored grains come as a Placement");
    assemble();
    m_dem->resume(static_cast<std::uint64_t>(stepsDone), time);
    m_steps = stepsDone;
}

void Simulation::assemble() {
    m_sync =
        std::make_unique<particles::ParticleSync>(*m_comm, *m_placed.particleForest, m_setup.sync);
    if (m_setup.selfGravity)
        m_gravity =
            std::make_unique<SelfGravityForces>(*m_comm, *m_placed.forest, *m_setup.selfGravity);
    m_dem = std::make_unique<particles::DemStep>(*m_comm, *m_sync, *m_placed.local,
                                                 *m_setup.contact, m_setup.integrator,
                                                 m_setup.walls, m_setup.dem, m_timers);
    // Self-gravity first, then the program's own (after the contacts and their reduction).
    // Self-gravity's check for grains that changed rank rides on the step's vote.
    if (m_gravity)
        m_dem->setBodyForceVote(
            [this](particles::LocalParticles const& local) { return m_gravity->voteShare(local); });
    if (m_gravity || !m_bodyForces.empty())
        m_dem->setBodyForces([this](particles::LocalParticles& local) {
            if (m_gravity)
                m_gravity->addForces(local, m_dem->bodyForceVote());
            for (BodyForces const& f : m_bodyForces)
                f(local);
        });
}

double Simulation::time() const {
    return m_dem ? m_dem->time() : 0.0;
}

void Simulation::relocated() {
    m_sync->relocate(*m_placed.particleForest);
    if (m_gravity)
        m_gravity->relocate(*m_placed.forest);
    m_dem->relocated();
}

bool Simulation::needed(std::int64_t step, bool ObserverNeeds::*need) const {
    return std::any_of(m_observers.begin(), m_observers.end(),
                       [&](Watch const& w) { return w.needs.*need && w.due(step); });
}

RunStats Simulation::run(std::int64_t steps) {
    if (!m_dem)
        throw core::Error("Simulation::run before start() or resume()");
    using StepEnd = particles::DemStep::StepEnd;
    particles::DemStep& dem = *m_dem;
    m_timers.reset();
    m_sync->resetCounters();
    std::uint64_t const leftBefore = dem.leftDomain();
    std::uint64_t const crossedBefore = dem.wallCrossings().count;
    std::uint64_t const rebuildsBefore = dem.listRebuilds();
    std::uint64_t const shiftsBefore = dem.listShifts();
    m_comm->barrier(); // every rank starts the clock together
    double const started = MPI_Wtime();
    for (std::int64_t n = 0; n < steps; ++n) {
        std::int64_t const next = m_steps + 1;
        dem.setKeepContacts(m_setup.dem.keepContacts || needed(next, &ObserverNeeds::contacts));
        // A step no observer looks at ends open: its last half kick merged into the next's.
        bool const complete = n + 1 == steps || needed(next, &ObserverNeeds::completeGrains);
        dem.step(complete ? StepEnd::Complete : StepEnd::Open);
        m_steps = next;
        for (Watch const& w : m_observers)
            if (w.due(m_steps))
                w.observer(*this);
    }
    double const elapsed = MPI_Wtime() - started;

    RunStats out;
    out.steps = steps;
    out.wallSeconds = m_comm->allReduce(elapsed, core::ReduceOp::Max);
    out.timers = m_timers.reduce(*m_comm);
    out.comm = m_sync->counters().reduce(*m_comm);
    auto const& crossings = dem.wallCrossings();
    std::array<long long, 4> counts{static_cast<long long>(dem.leftDomain() - leftBefore),
                                    static_cast<long long>(dem.listRebuilds() - rebuildsBefore),
                                    static_cast<long long>(crossings.count - crossedBefore),
                                    static_cast<long long>(dem.listShifts() - shiftsBefore)};
    m_comm->allReduceInPlace(std::span<long long>(counts), core::ReduceOp::Sum);
    out.leftDomain = counts[0];
    out.listRebuilds = counts[1];
    out.leftThroughWalls = counts[2];
    out.listShifts = counts[3];
    if (out.leftThroughWalls > 0) { // the earliest step's, lowest uid's (every rank is here)
        bool const mine = crossings.count > crossedBefore;
        auto const when = m_comm->allGather<std::uint64_t>(
            mine ? crossings.firstStep : std::numeric_limits<std::uint64_t>::max());
        auto const uids = m_comm->allGather<std::uint64_t>(crossings.firstUid);
        auto const walls = m_comm->allGather<std::uint64_t>(crossings.firstWall);
        std::size_t first = 0;
        for (std::size_t r = 1; r < when.size(); ++r)
            if (when[r] < when[first] || (when[r] == when[first] && uids[r] < uids[first]))
                first = r;
        out.firstWallCrossing = fmt::format("particle uid {} at step {} through walls[{}]",
                                            uids[first], when[first], walls[first]);
    }
    out.listSkin = m_comm->allReduce(dem.listSkin(), core::ReduceOp::Max);
    return out;
}

} // namespace regolith::coupling
