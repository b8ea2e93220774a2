#include "coupling/simulation/Simulation.hpp"

#include "core/Error.hpp"
#include "coupling/balance/BlockWeights.hpp"
#include "particles/integration/TimeStepGuard.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <algorithm>
#include <utility>
#include <variant>

namespace regolith::coupling {

namespace {

bool usesGrid(std::optional<SelfGravityConfig> const& gravity) {
    return gravity && (gravity->method == GrainGravityMethod::Mesh ||
                       gravity->method == GrainGravityMethod::P3m);
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
    if (usesGrid(m_setup.selfGravity))
        m_setup.domain.cellsPerBlock = m_setup.selfGravity->cellsPerBlock;
}

Simulation::~Simulation() = default;

void Simulation::addGrain(particles::ParticleInit const& grain) {
    if (m_dem)
        throw core::Error("Simulation::addGrain after start()");
    m_pending.push_back(grain);
}

void Simulation::addBodyForces(BodyForces forces) {
    m_bodyForces.push_back(std::move(forces));
}

void Simulation::addObserver(std::int64_t every, Observer observer) {
    if (every < 1)
        throw core::InputError(
            fmt::format("Simulation::addObserver: every {}: expected >= 1", every));
    m_observers.push_back({every, std::move(observer)});
}

void Simulation::place(domain::BlockWeight const& weight) {
    auto [blocks, subdomains] =
        domain::BlockForest::blocksAnd(*m_comm, m_setup.domain, weight, m_setup.subdomains);
    m_forest = std::make_unique<domain::BlockForest>(std::move(blocks));
    m_particleForest = std::make_unique<domain::BlockForest>(std::move(subdomains));
    m_local = std::make_unique<particles::LocalParticles>(*m_particleForest);
    for (particles::ParticleInit const& p : m_pending)
        (void)m_local->addMaster(p); // false: another rank's
}

void Simulation::checkTimeStep() const {
    particles::ContactTimeEstimate shortest;
    for (particles::BlockParticles const& block : m_local->blocks()) {
        particles::ContactTimeEstimate const e = std::visit(
            [&](auto const& model) -> particles::ContactTimeEstimate {
                // Hertz-Mindlin's contact time needs an impact speed: not guarded here.
                if constexpr (requires { particles::estimateContactTime(block.particles, model); })
                    return particles::estimateContactTime(block.particles, model);
                else
                    return {};
            },
            *m_setup.contact);
        if (e.contactTime < shortest.contactTime)
            shortest = e;
    }
    shortest = particles::shortestContactTime(*m_comm, shortest);
    particles::checkTimeStep(m_setup.dem.dt, shortest, m_setup.allowUnstable);
}

void Simulation::start() {
    if (m_dem)
        throw core::Error("Simulation::start called twice");
    // Every rank was given the same grains: each keeps its own, and together they keep all.
    auto const given = static_cast<long long>(m_pending.size());
    if (m_comm->allReduce(given, core::ReduceOp::Min) !=
        m_comm->allReduce(given, core::ReduceOp::Max))
        throw core::InputError("Simulation::start: the ranks were given different numbers of "
                               "grains (addGrain: every rank gives every grain)");
    place({});
    BlockLoadModel load;
    if (usesGrid(m_setup.selfGravity))
        load = {m_setup.domain.cellsPerBlock, m_setup.domain.cellWeight};
    place(grainAndCellWeights(*m_comm, *m_local, load)); // the grains' load, along the curve
    m_pending.clear();
    m_pending.shrink_to_fit();
    auto const kept =
        m_comm->allReduce(static_cast<long long>(m_local->countMasters()), core::ReduceOp::Sum);
    if (kept != given)
        throw core::InputError(fmt::format("Simulation::start: {} of {} grains lie outside the "
                                           "domain or were given twice",
                                           given - kept, given));

    checkTimeStep();

    m_sync = std::make_unique<particles::ParticleSync>(*m_comm, *m_particleForest, m_setup.sync);
    if (m_setup.selfGravity)
        m_gravity = std::make_unique<SelfGravityForces>(*m_comm, *m_forest, *m_setup.selfGravity);
    m_dem = std::make_unique<particles::DemStep>(*m_comm, *m_sync, *m_local, *m_setup.contact,
                                                 m_setup.integrator, m_setup.walls, m_setup.dem,
                                                 m_timers);
    if (m_gravity || !m_bodyForces.empty())
        m_dem->setBodyForces([this](particles::LocalParticles& local) {
            if (m_gravity)
                m_gravity->addForces(local);
            for (BodyForces const& f : m_bodyForces)
                f(local);
        });
    m_dem->setUp();
}

bool Simulation::observed(std::int64_t step) const {
    return std::any_of(m_observers.begin(), m_observers.end(),
                       [step](Watch const& w) { return step % w.every == 0; });
}

void Simulation::run(std::int64_t steps) {
    if (!m_dem)
        throw core::Error("Simulation::run before start()");
    using StepEnd = particles::DemStep::StepEnd;
    for (std::int64_t n = 0; n < steps; ++n) {
        std::int64_t const next = m_steps + 1;
        // A step nobody looks at ends open: its last half kick is merged into the next step's.
        bool const complete = n + 1 == steps || observed(next);
        m_dem->step(complete ? StepEnd::Complete : StepEnd::Open);
        m_steps = next;
        for (Watch const& w : m_observers)
            if (m_steps % w.every == 0)
                w.observer(*this);
    }
}

} // namespace regolith::coupling
