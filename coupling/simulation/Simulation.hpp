#pragma once
/// A coupled run as a library object: the block forest, the grains on it, the shadow
/// synchronisation, the DEM step and self-gravity, put together from plain settings, with
/// hooks for what a program of one's own adds (docs/design.md, "The time step"):
///
///     integrate (first half kick, drift)        moves the masters
///     sync                                      shadows follow their masters (NNS / SOS)
///     contacts, per block                       detect and evaluate
///     reduce                                    shadows' forces to their masters
///     body forces                               self-gravity when set, then every addBodyForces
///     integrate (second half kick)              merged into the next step's first when no
///                                               observer looks at the grains in between
///     observers due at this step                read the grains, may change their velocities
///
/// The grains are given on every rank alike (addGrain), and the blocks are then assigned to
/// the ranks by the load of those grains along the Hilbert curve; or each rank gives its own,
/// already placed (a Placement: generated in parallel, or read from a checkpoint). The
/// particles run on each rank's blocks merged into cuboids (sync.subdomains "merged"), so the
/// block count is chosen for the grid and the balance, not the speed.
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "core/timing/TimerTree.hpp"
#include "coupling/gravity/SelfGravityForces.hpp"
#include "coupling/simulation/Placement.hpp"
#include "coupling/simulation/RunStats.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/simulation/DemStep.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace regolith::coupling {

/// What a run is made of. The defaults are the scene file's.
struct SimulationSetup {
    domain::ForestSpec domain;  ///< box, periodic axes, root blocks (several per rank is fine)
    particles::SyncConfig sync; ///< NNS / SOS / hybrid, reproducible mode, shadow skin
    /// dt (required), uniform external gravity, list skin; the pair contacts are kept for
    /// dem().contacts() after every step only with keepContacts (it costs a copy of every
    /// contact every step), else after the steps of observers that ask for them.
    particles::DemStepConfig dem = [] {
        particles::DemStepConfig c;
        c.keepContacts = false;
        return c;
    }();
    std::optional<particles::AnyContactModel> contact; ///< required: the contact law
    /// Run even with dem.dt above a tenth of the shortest contact time (TimeStepGuard; the
    /// guard covers the spring-dashpot and laws of one's own, not Hertz-Mindlin, whose contact
    /// time depends on the impact speed).
    bool allowUnstable = false;
    particles::AnyIntegrator integrator = particles::VelocityVerlet{};
    particles::WallList walls;
    std::optional<SelfGravityConfig> selfGravity; ///< none: no self-gravity
    /// sync.subdomains: each rank's blocks merged into cuboids (the default) or one particle
    /// subdomain per block.
    domain::Subdomains subdomains = domain::Subdomains::RankBoxes;
};

class Simulation {
public:
    /// Forces or torques of one's own, added to the masters after contacts and self-gravity
    /// in every force computation (ParticleStorage::force / torque of each master).
    using BodyForces = std::function<void(particles::LocalParticles&)>;
    /// Called after a step (see ObserverNeeds): may read every master and change velocities;
    /// `Simulation::stepsDone()` and `time()` tell which step.
    using Observer = std::function<void(Simulation&)>;
    /// Whether an observer is due after the step that leaves `stepsDone` steps done; the same
    /// answer on every rank.
    using Due = std::function<bool(std::int64_t stepsDone)>;
    /// What an observer needs when it is due.
    struct ObserverNeeds {
        /// The grains complete (positions and velocities of the same time). false: they may
        /// be half a kick behind (a progress line, counters, the positions and
        /// dem().contactsOfLastPass() a load measurement reads), and the step stays open; such
        /// an observer calls dem().completeStep() before it reads or changes more.
        bool completeGrains = true;
        /// The step's pair contacts in dem().contacts() (they are kept only where asked).
        bool contacts = false;
    };

    /// Keeps the settings, refusing (core::InputError) a missing contact model, a dt that is
    /// not positive and a self-gravity method nobody registered (GravityMethod.hpp). Not
    /// collective; `comm` must outlive the object.
    Simulation(core::Comm const& comm, SimulationSetup setup);
    /// The same with the grains already on their ranks, each rank its own masters in
    /// `placed.local` (setup.domain and setup.subdomains are then those of `placed`). The
    /// caller has checked them (inside the domain, the time step). Not collective.
    Simulation(core::Comm const& comm, SimulationSetup setup, Placement placed);
    ~Simulation();
    Simulation(Simulation const&) = delete;
    Simulation& operator=(Simulation const&) = delete;

    /// Before start(): a grain, given alike on every rank (uid unique, inside the domain).
    void addGrain(particles::ParticleInit const& grain);
    void addBodyForces(BodyForces forces);
    /// `observer` runs after every step whose number is a multiple of `every` (>= 1).
    void addObserver(std::int64_t every, Observer observer);
    /// `observer` runs after the steps `due` names, in the order the observers were added.
    void addObserver(Due due, Observer observer, ObserverNeeds needs);

    /// Places the grains given by addGrain on the ranks by their load (unless the Simulation
    /// was given a Placement), creates the shadows and computes the initial forces. Throws
    /// core::InputError on every rank if the ranks were given different grains, a grain lies
    /// outside the domain, or dt exceeds a tenth of the shortest contact time (unless
    /// allowUnstable). COLLECTIVE.
    void start();
    /// Instead of start(), for grains restored from a checkpoint with their forces, torques
    /// and contact histories: creates the shadows and continues after `stepsDone` steps at
    /// simulated time `time`, computing no forces (DemStep::resume). COLLECTIVE.
    void resume(std::int64_t stepsDone, double time);
    /// `steps` time steps (start() or resume() first); the grains are complete on return.
    /// The timers and traffic counters cover these steps only. COLLECTIVE.
    RunStats run(std::int64_t steps);
    /// After the grains moved between ranks (the Placement's contents replaced, e.g. by a
    /// rebalance or an insertion): rebuilds what stands on the old assignment (the
    /// synchronisation's plans, the contact lists, the gravity grid). COLLECTIVE.
    void relocated();

    [[nodiscard]] std::int64_t stepsDone() const { return m_steps; }
    /// Simulated time after stepsDone(): the start's (0, or resume's) plus dt per step.
    [[nodiscard]] double time() const;
    [[nodiscard]] core::Comm const& comm() const { return *m_comm; }
    [[nodiscard]] SimulationSetup const& setup() const { return m_setup; }
    /// The forest of blocks (grid fields, output) and the grains on its ranks' subdomains.
    [[nodiscard]] domain::BlockForest const& forest() const { return *m_placed.forest; }
    [[nodiscard]] particles::LocalParticles& grains() { return *m_placed.local; }
    [[nodiscard]] particles::LocalParticles const& grains() const { return *m_placed.local; }
    /// The forests and the grains, for what moves grains between ranks (then relocated()).
    [[nodiscard]] Placement& placement() { return m_placed; }
    /// Calls `f(storage, i)` for every master of this rank.
    template <class F>
    void forEachGrain(F&& f) {
        for (particles::BlockParticles& block : m_placed.local->blocks())
            block.particles.forEachMaster([&](std::size_t i) { f(block.particles, i); });
    }
    /// After start() or resume():
    [[nodiscard]] particles::DemStep& dem() { return *m_dem; }
    [[nodiscard]] particles::DemStep const& dem() const { return *m_dem; }
    [[nodiscard]] particles::ParticleSync& sync() { return *m_sync; }
    [[nodiscard]] SelfGravityForces* selfGravity() { return m_gravity.get(); }
    [[nodiscard]] SelfGravityForces const* selfGravity() const { return m_gravity.get(); }
    /// Time per phase ("integrate", "sync", "contact", "gravity", ...), this rank's.
    [[nodiscard]] core::TimerTree const& timers() const { return m_timers; }

private:
    struct Watch {
        Due due;
        Observer observer;
        ObserverNeeds needs;
    };
    void place(domain::BlockWeight const& weight);
    void checkTimeStep() const;
    /// The synchronisation, self-gravity and the DEM step on the placed grains.
    void assemble();
    /// Whether an observer due after step `step` needs what `need` selects.
    [[nodiscard]] bool needed(std::int64_t step, bool ObserverNeeds::*need) const;

    core::Comm const* m_comm;
    SimulationSetup m_setup;
    std::vector<particles::ParticleInit> m_pending; ///< the grains until start()
    bool m_placedByCaller = false;
    std::vector<BodyForces> m_bodyForces;
    std::vector<Watch> m_observers;
    Placement m_placed;
    std::unique_ptr<particles::ParticleSync> m_sync;
    std::unique_ptr<SelfGravityForces> m_gravity;
    core::TimerTree m_timers;
    std::unique_ptr<particles::DemStep> m_dem;
    std::int64_t m_steps = 0;
};

} // namespace regolith::coupling
