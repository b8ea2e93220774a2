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
/// The grains are given on every rank alike (addGrain); each rank keeps those in its blocks.
/// The blocks are assigned to the ranks by the load of those grains along the Hilbert curve,
/// and the particles run on each rank's blocks merged into cuboids (sync.subdomains
/// "merged"), so the block count is chosen for the grid and the balance, not the speed.
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "core/timing/TimerTree.hpp"
#include "coupling/gravity/SelfGravityForces.hpp"
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
    /// dt (required), uniform external gravity, list skin; the pair contacts are not kept
    /// for dem().contacts() after each step unless keepContacts is set (as in the driver: it
    /// costs a copy of every contact every step).
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
    /// Called after a step with the grains complete (positions and velocities of the same
    /// time): may read every master and change velocities; `Simulation::step*()` tell which.
    using Observer = std::function<void(Simulation&)>;

    /// Keeps the settings, refusing (core::InputError) a missing contact model and a dt that is
    /// not positive. Not collective; `comm` must outlive the object.
    Simulation(core::Comm const& comm, SimulationSetup setup);
    ~Simulation();
    Simulation(Simulation const&) = delete;
    Simulation& operator=(Simulation const&) = delete;

    /// Before start(): a grain, given alike on every rank (uid unique, inside the domain).
    void addGrain(particles::ParticleInit const& grain);
    void addBodyForces(BodyForces forces);
    /// `observer` runs after every step whose number is a multiple of `every` (>= 1).
    void addObserver(std::int64_t every, Observer observer);

    /// Places the grains on the ranks by their load, creates the shadows and computes the
    /// initial forces. Throws core::InputError on every rank if the ranks were given different
    /// grains, a grain lies outside the domain, or dt exceeds a tenth of the shortest contact
    /// time (unless allowUnstable). COLLECTIVE.
    void start();
    /// `steps` time steps (start() first); the grains are complete on return. COLLECTIVE.
    void run(std::int64_t steps);

    [[nodiscard]] std::int64_t stepsDone() const { return m_steps; }
    [[nodiscard]] double time() const { return static_cast<double>(m_steps) * m_setup.dem.dt; }
    [[nodiscard]] core::Comm const& comm() const { return *m_comm; }
    /// The forest of blocks (grid fields, output) and the grains on its ranks' subdomains.
    [[nodiscard]] domain::BlockForest const& forest() const { return *m_forest; }
    [[nodiscard]] particles::LocalParticles& grains() { return *m_local; }
    [[nodiscard]] particles::LocalParticles const& grains() const { return *m_local; }
    /// Calls `f(storage, i)` for every master of this rank.
    template <class F>
    void forEachGrain(F&& f) {
        for (particles::BlockParticles& block : m_local->blocks())
            block.particles.forEachMaster([&](std::size_t i) { f(block.particles, i); });
    }
    [[nodiscard]] particles::DemStep const& dem() const { return *m_dem; }
    [[nodiscard]] SelfGravityForces const* selfGravity() const { return m_gravity.get(); }
    /// Time per phase ("integrate", "sync", "contact", "gravity", ...), this rank's.
    [[nodiscard]] core::TimerTree const& timers() const { return m_timers; }

private:
    struct Watch {
        std::int64_t every;
        Observer observer;
    };
    void place(domain::BlockWeight const& weight);
    void checkTimeStep() const;
    [[nodiscard]] bool observed(std::int64_t step) const;

    core::Comm const* m_comm;
    SimulationSetup m_setup;
    std::vector<particles::ParticleInit> m_pending; ///< the grains until start()
    std::vector<BodyForces> m_bodyForces;
    std::vector<Watch> m_observers;
    std::unique_ptr<domain::BlockForest> m_forest;
    std::unique_ptr<domain::BlockForest> m_particleForest;
    std::unique_ptr<particles::LocalParticles> m_local;
    std::unique_ptr<particles::ParticleSync> m_sync;
    std::unique_ptr<SelfGravityForces> m_gravity;
    core::TimerTree m_timers;
    std::unique_ptr<particles::DemStep> m_dem;
    std::int64_t m_steps = 0;
};

} // namespace regolith::coupling
