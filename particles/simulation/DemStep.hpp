#pragma once
/// The DEM time step of one rank over all its local blocks (docs/design.md, "The time step"):
/// velocity Verlet (or semi-implicit Euler) split around the force computation, the shadow
/// synchronisation between the moves and the contacts, contact detection and evaluation per
/// block, and the reduction of shadow forces to the masters.
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "core/timing/TimerTree.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/ContactDetector.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/integration/SemiImplicitEuler.hpp"
#include "particles/integration/VelocityVerlet.hpp"
#include "particles/kernels/ContactLaw.hpp"
#include "particles/kernels/ForceRecord.hpp"
#include "particles/kernels/HertzMindlin.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/simulation/AnyContactModel.hpp"
#include "particles/simulation/BlockContactLoop.hpp"
#include "particles/storage/WallList.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"
#include "particles/sync/SyncInvariants.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace regolith::particles {

/// The integrators a run may choose (scene key time.integrator).
using AnyIntegrator = std::variant<VelocityVerlet, SemiImplicitEuler>;

struct DemStepConfig {
    double dt = 0.0;                         ///< time step [time], > 0 and finite
    core::Vec3 gravity = core::Vec3::Zero(); ///< uniform external acceleration [length/time^2]
    /// Contact detection of every block: by default a Verlet list with a skin of a quarter of
    /// the small grains' radius, widened up to three quarters where that lists hardly more
    /// pairs (reused across steps; ContactDetector, "A skin for the scene").
    DetectorConfig detector{.skin = 0.0, .relativeSkin = 0.25, .widestRelativeSkin = 0.75};
    /// Check the synchronisation invariants (particles/sync/SyncInvariants.hpp) over all
    /// ranks after every sync call and throw core::Error on every rank if one fails. A
    /// debugging aid (it gathers every copy on rank 0); on by default in builds with
    /// REGOLITH_CHECK_INVARIANTS.
    bool checkInvariants = kCheckSyncInvariants;
    /// Keep every step's contacts for contacts(). false: contacts() holds the wall contacts of
    /// the last force computation and the pair contacts of the set-up's only (stamp 0, what
    /// the driver checks), which saves writing every pair contact (96 bytes) each step.
    bool keepContacts = true;
    /// Keep the tangential springs of the pairs deep inside a block beside its Verlet list
    /// between Complete steps (ContactDetector, "Springs kept beside the list"; with the
    /// spring-dashpot model without model C's rolling spring): the same bits, one history
    /// look-up fewer per contact and step.
    bool keepSprings = true;
};

/// One DEM run's time stepping over the blocks of `LocalParticles`. It holds one contact
/// detector per local block, the contact model, the integrator and the walls; the caller owns
/// the communicator, the particles, the synchronisation and the timers (which must outlive
/// this object).
///
/// The step (every member below that says so is COLLECTIVE over the communicator of `sync`):
///
///     integrator.preForce    on every block          (timer "integrate"; moves masters only)
///     the agreement before the sync                  (one all-reduce, more than one rank)
///     sync.syncOn(local, its verdict)                (timer "sync")
///     the body forces' vote share (setBodyForceVote)  (timer "gravity")
///     the agreement after the sync: list rebuilds,   (one all-reduce, more than one rank, in
///     that share, the sync list's hold               the steps that need it)
///     per block: resetForces, detect (region = block box, periodic frame of the forest),
///                evaluate with stamp = step number   (timer "contact")
///     sync.reduceForces(local[, records], stamp)     (timer "sync")
///     body forces (setBodyForces), e.g. self-gravity  (timer "gravity")
///     integrator.postForce   on every block          (timer "integrate"; with StepEnd::Open
///                            merged into the next step's preForce)
///
/// In reproducible mode (sync.config().reproducible) every block evaluates with
/// evaluateContactsRecorded and the reduction sums every master's force from its records in
/// ascending partner uid, so that the trajectory does not depend on the number of ranks or
/// blocks (docs/design.md, "Reproducible mode"); otherwise forces are accumulated in place and the
/// shadows' shares added to the masters.
///
/// Between two sync calls only the integrator moves masters (the caller must not move
/// grains between steps; resume() and setUp() start afresh): the largest distance it moved a
/// copy (Integrator) bounds every master's displacement, and every shadow's (a copy of its
/// master, shifted by a period), so the sync skin and the Verlet lists are told that bound
/// instead of comparing every position with their references each step. On more than one rank
/// the bound is the largest over all ranks (a block's shadows may have their masters
/// elsewhere), as LAMMPS's Neighbor::decide does. What the ranks agree on, and when:
/// StepAgreement.hpp.
///
/// With DemStepConfig::checkInvariants (the default in builds with REGOLITH_CHECK_INVARIANTS)
/// the synchronisation invariants are checked over all ranks after every sync call, where
/// they hold (postForce then changes the masters' velocities, not their shadows').
///
/// Walls are global: every block tests its copies against every wall, and the detector keeps
/// a sphere-wall contact only for the sphere's master, so exactly one block evaluates it.
/// Before each force computation the moving walls are put where their motion has them at the
/// step's time (time() after it). The walls' loads (walls().load) are this rank's share of the
/// last evaluation and their work (walls().work) this rank's share since the start, not
/// reduced over ranks.
class DemStep {
public:
    /// Timer names (children of whatever scope is open when step() is called).
    static constexpr std::string_view kSyncTimer = "sync";
    static constexpr std::string_view kContactTimer = "contact";
    static constexpr std::string_view kIntegrateTimer = "integrate";
    /// The body forces (self-gravity) of setBodyForces.
    static constexpr std::string_view kBodyForceTimer = "gravity";

    /// Forces that do not come from contacts, e.g. self-gravity (coupling/): called with the
    /// local particles after every contact evaluation and force reduction (set-up and every
    /// step), it adds to the masters' force and torque. It must be COLLECTIVE over the same
    /// communicator if it communicates (it is called on every rank at the same point).
    using BodyForces = std::function<void(LocalParticles&)>;
    /// A body force's share of a vote of all ranks (e.g. self-gravity's: whether a grain here
    /// has no field record, gravity::UpdatePolicy::localVerdict): called with the local
    /// particles after the synchronisation, before the contacts (timer "gravity"), not
    /// collective; the element-wise maximum over the ranks is taken in the reduction that
    /// decides the Verlet list rebuilds, so the body forces need no reduction of their own.
    using BodyForceVote = std::function<std::array<double, 2>(LocalParticles const&)>;

    /// Pre: `comm` is the communicator `sync` was built from (or a duplicate), `local`
    /// belongs to the forest `sync` was built for; config.dt > 0 and finite (throws
    /// core::Error otherwise). Not collective.
    DemStep(core::Comm const& comm, ParticleSync& sync, LocalParticles& local,
            AnyContactModel model, AnyIntegrator integrator, WallList walls, DemStepConfig config,
            core::TimerTree& timers);

    /// Before the first step, after the masters were added: refuses a scene NNS cannot
    /// simulate (ParticleSync::requireNnsApplicable: core::InputError on every rank, naming
    /// the uid, its radius, the block edge and the remedy), synchronises until every shadow
    /// exists (syncUntilConverged; returns the number of calls), and computes the forces of
    /// the initial state with stamp 0, so that the first half kick of velocity Verlet sees
    /// them. COLLECTIVE.
    int setUp();

    /// Instead of setUp(), for a run restarted from a checkpoint: the masters were added
    /// with the force, torque and contact history of the step `stepsDone` they were saved
    /// at. Refuses what setUp refuses, synchronises until every shadow exists, and continues
    /// the step numbering (history stamps) after `stepsDone`. It computes no forces: the
    /// restored ones are those velocity Verlet's next half kick must see, and evaluating the
    /// contacts again would advance the tangential springs a second time. Returns the number
    /// of sync calls. COLLECTIVE.
    int resume(std::uint64_t stepsDone);
    /// As resume(stepsDone), the checkpoint's step having been reached at simulated time
    /// `time` (where the walls' motion stands; resume(stepsDone) takes stepsDone * dt).
    int resume(std::uint64_t stepsDone, double time);

    /// After the grains were moved to other blocks or ranks between two steps (a
    /// rebalance: `local` and the synchronisation now stand on another assignment of the
    /// blocks, the masters carry force, torque and contact history as after a Complete step):
    /// the per-block detectors and lists start anew for the new blocks and the run goes on as
    /// after resume(stepsDone()), the trajectory the same bit for bit. Throws core::Error if
    /// the last step ended Open. Returns the number of sync calls. COLLECTIVE.
    int relocated();

    /// How a step ends. Complete: with the second half kick (postForce), the velocities those
    /// of the step's end. Open: the half kick is left to the next step, which applies it in
    /// the same pass over the grains as its own first one (the integrator's postThenPreForce,
    /// where it has one: each grain's state read and written once instead of twice; the
    /// trajectory the same bit for bit). After an Open step the velocities and angular
    /// velocities lag half a kick, and the tangential springs of the pairs deep inside a block
    /// may still be kept beside its Verlet list (ContactDetector, "Springs kept beside the
    /// list"; a Complete step writes them back), so nothing may read the grains' state beyond
    /// their positions and contactsOfLastPass(), or change it, before the next step() or
    /// completeStep(): a time loop ends a step Open only when no output, checkpoint or other
    /// observer that reads more follows it (coupling/simulation/Simulation.hpp).
    enum class StepEnd { Complete, Open };

    /// One time step (see the class comment); the step number (stamp) is stepsDone() + 1.
    /// Throws what the synchronisation throws (core::Error: a grain too fast or too large
    /// for NNS, a malformed message). COLLECTIVE.
    void step(StepEnd end = StepEnd::Complete);
    /// Applies the half kick an Open step left (nothing otherwise). Not collective.
    void completeStep();
    /// Whether the last step ended Complete (or completeStep() was called since).
    [[nodiscard]] bool stepComplete() const { return !m_kickPending; }

    /// Frees the contact detectors' work arrays and neighbour lists and the contact lists
    /// (e.g. after the last step, before gathering output); the next step rebuilds them.
    /// Not collective.
    void releaseWorkspace();

    /// Whether the following force computations keep their pair contacts for contacts()
    /// (DemStepConfig::keepContacts), e.g. for the one step whose contacts are reported.
    void setKeepContacts(bool keep) { m_config.keepContacts = keep; }

    /// Installs the body forces (see BodyForces); an empty function removes them. Call it
    /// before setUp(), so that the initial forces include them.
    void setBodyForces(BodyForces forces) { m_bodyForces = std::move(forces); }
    /// Installs a body force's vote (see BodyForceVote); an empty function removes it. Call it
    /// before setUp().
    void setBodyForceVote(BodyForceVote share) { m_bodyForceShare = std::move(share); }
    /// The maximum over the ranks of every rank's BodyForceVote share in the current force
    /// computation (zeros without a vote): for the body forces. Not collective.
    [[nodiscard]] std::array<double, 2> const& bodyForceVote() const { return m_bodyForceVote; }

    /// Simulated time after stepsDone() steps: the start's (0, or resume's) plus dt per step.
    [[nodiscard]] double time() const {
        return m_startTime + static_cast<double>(m_steps - m_startStep) * m_config.dt;
    }
    /// Steps done: since construction, plus the checkpoint's steps after resume().
    [[nodiscard]] std::uint64_t stepsDone() const { return m_steps; }
    /// Masters this rank removed because they left an open domain, over all steps (set-up
    /// removes none: every master starts in the block containing it). Local: sum over ranks
    /// for the run's total.
    [[nodiscard]] std::uint64_t leftDomain() const { return m_leftDomain; }
    /// Of those, the masters found behind a wall when they left: they passed through it in
    /// one step (dt |v| beyond their radius), which no open face explains. Local.
    struct WallCrossings {
        std::uint64_t count = 0;
        Uid firstUid = kInvalidUid;  ///< the first one this rank found
        std::uint64_t firstStep = 0; ///< at this step
        std::size_t firstWall = 0;   ///< through walls[firstWall]
    };
    [[nodiscard]] WallCrossings const& wallCrossings() const { return m_wallCrossings; }
    /// Verlet-list rebuilds of the local blocks' detectors over all force computations (a
    /// block's rebuild counts once; a block without copies counts none). Local: sum over
    /// ranks for the run's total.
    [[nodiscard]] std::uint64_t listRebuilds() const { return m_listRebuilds; }
    /// Verlet-list shifts with the grains' drift instead of rebuilds (ContactDetector, "A list
    /// that follows a drift"), counted as listRebuilds. Local.
    [[nodiscard]] std::uint64_t listShifts() const { return m_listShifts; }
    /// Pairs whose springs the local blocks' Verlet lists keep (DemStepConfig::keepSprings),
    /// as of the last force computation. Local.
    [[nodiscard]] std::size_t keptPairs() const { return detectorSum(&DetectorStats::keptPairs); }
    /// Each master's contacts of the last force computation, block by block: its history
    /// entries that computation stamped and the kept springs it touched that live beside a
    /// Verlet list (ContactDetector::countKeptContacts), so that an Open step need not write
    /// them back to be counted. Shadows count 0. Local.
    [[nodiscard]] ContactCounts contactsOfLastPass() const;
    /// The skin of the local blocks' last list rebuild (the largest, if several rebuilt in that
    /// step) [length], kept across a relocation that renews the lists; 0 without a list
    /// (DemStepConfig::detector without a skin) or before the first rebuild. Local.
    [[nodiscard]] double listSkin() const { return m_listSkin; }
    /// The contacts each local block evaluated in the last force computation (indices into
    /// that block's storage; valid until the next synchronisation), in the order of
    /// LocalParticles::blocks(). With DemStepConfig::keepContacts false, the pair contacts
    /// are those of setUp() only (empty after a step).
    [[nodiscard]] std::span<ContactList const> contacts() const { return m_contacts; }
    [[nodiscard]] WallList const& walls() const { return m_walls; }
    [[nodiscard]] DemStepConfig const& config() const { return m_config; }
    [[nodiscard]] PeriodicFrame const& frame() const { return m_frame; }

private:
    /// Sizes the per-block state (detectors, contact lists, reach) for the blocks of m_local.
    void placeOnBlocks();
    /// The step's synchronisation (DemStepSync.cpp): refuses, on every rank, a motion beyond
    /// the neighbour blocks the sync reaches, writes kept springs back where a copy may
    /// migrate, syncs, and counts the grains that left the domain or crossed a wall. COLLECTIVE.
    void syncParticles();
    /// How far beyond its radius a grain's copies reach: the sync skin and half the contact
    /// model's range (what the invariant checks allow).
    [[nodiscard]] double copySkin() const;
    /// A count of the local blocks' last detections, summed (DetectorStats).
    [[nodiscard]] std::size_t detectorSum(std::size_t DetectorStats::*count) const;
    /// Writes the springs the blocks' Verlet lists keep back to the grains' histories
    /// (ContactDetector, "Springs kept beside the list"): where a step ends Complete, before
    /// anything may read the grains. Not collective.
    void writeBackSprings();
    /// Detection, evaluation and reduction with stamp `stamp`. COLLECTIVE.
    void computeForces(std::uint32_t stamp);
    /// On several ranks, before the detections, the step's agreement after the sync
    /// (StepAgreement.hpp), where one is needed: when some block's Verlet list is due for a
    /// rebuild on some rank, every block whose list has used half its skin rebuilds it in this
    /// step too (ContactDetector::prepareList). Lists that rebuild at their own steps keep
    /// the other ranks waiting, in turns, at the force reduction; moving bodies use their
    /// skins at similar rates, so after one common rebuild they stay in step. Returns whether
    /// the sync skin's list holds on every rank (ParticleSync::listHoldsHere). COLLECTIVE.
    bool agreeAfterSync();

    core::Comm const* m_comm;
    ParticleSync* m_sync;
    LocalParticles* m_local;
    AnyContactModel m_model;
    AnyIntegrator m_integrator;
    WallList m_walls;
    DemStepConfig m_config;
    core::TimerTree* m_timers;
    PeriodicFrame m_frame;
    std::vector<ContactDetector> m_detectors;        ///< one per local block
    std::vector<char> m_listHalfway;                 ///< agreeAfterSync, per block
    std::vector<ContactList> m_contacts;             ///< one per local block
    std::vector<std::vector<ForceRecord>> m_records; ///< one per local block (reproducible)
    std::unique_ptr<BlockContactLoop> m_loop;        ///< m_model's per-block contact loop
    BodyForces m_bodyForces;
    BodyForceVote m_bodyForceShare;
    std::array<double, 2> m_bodyForceVote{}; ///< this force computation's, reduced
    /// Bound on every copy's displacement since the last sync call, on this rank (+inf:
    /// unknown, before the first step).
    double m_moved = std::numeric_limits<double>::infinity();
    /// Per local block, the largest displacement since the last sync call over m_reachEdge
    /// (measured, never +inf for "unknown"): what syncParticles checks against 1.
    std::vector<double> m_movedSinceSync;
    /// Per local block, the smallest edge of it and its neighbours: a master that moves
    /// farther in one step may skip the neighbour blocks the sync reaches.
    std::vector<double> m_reachEdge;
    /// This step's agreement before the sync found that no Verlet list can come due
    /// (BeforeSyncAgreement::listsMayComeDue): agreeAfterSync needs no reduction.
    bool m_listsQuiet = false;
    bool m_kickPending = false; ///< the last step ended Open
    std::uint64_t m_steps = 0;
    std::uint64_t m_startStep = 0; ///< the step at m_startTime (set-up's or resume's)
    double m_startTime = 0.0;
    std::uint64_t m_leftDomain = 0;
    WallCrossings m_wallCrossings;
    std::uint64_t m_listRebuilds = 0;
    std::uint64_t m_listShifts = 0;
    double m_listSkin = 0.0; ///< listSkin()
};

} // namespace regolith::particles
