#pragma once
/// Self-gravity on the DEM grains (docs/design.md, "The time step": "body forces:
/// self-gravity if due"): gathers the masters of the local blocks, asks the update policy whether
/// the field must be recomputed, evaluates it with the method of the registry named in the
/// configuration (GravityMethod.hpp: direct sum, Barnes–Hut, the mutual tree, the mesh, P3M,
/// the second paper's node methods, or one a program registered) and adds m g to every
/// master's force. Installed into particles::DemStep as its body forces.
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/ForceErrorMonitor.hpp"
#include "domain/BlockForest.hpp"
#include "gravity/PoissonMethod.hpp"
#include "gravity/field/GridFieldsView.hpp"
#include "gravity/update/UpdatePolicy.hpp"
#include "particles/storage/Uid.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <any>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace regolith::coupling {

class GravityMethod;

struct SelfGravityConfig {
    /// gravity.self: a registered method's name (gravityMethodNames() in GravityMethod.hpp).
    std::string method = "direct";
    /// gravity.G [length^3 mass^-1 time^-2]; the default is SI's, a unit-free set-up sets it.
    double G = 6.674e-11;
    double softening = 0.0;           ///< gravity.softening, Plummer length [length]
    double theta = 0.5;               ///< gravity.theta (tree methods)
    bool allowLargeTheta = false;     ///< gravity.allow_large_theta
    double updateThreshold = 0.0;     ///< gravity.update_threshold [length]; 0: every step
    gravity::UpdateInterval interval; ///< gravity.update_every (field extrapolated between)
    /// sync.reproducible: each update from the local grains in uid order and (grid methods)
    /// each Poisson solve from zero, so that the field depends on the grains only, not on
    /// their storage order or the last solve: a restart, which has neither, repeats the bits.
    bool reproducible = false;
    // The grid methods only (GravityMethodEntry::usesGrid):
    std::array<int, 3> cellsPerBlock{0, 0, 0};                      ///< domain.cells_per_block
    std::string petscOptions;                                       ///< gravity.petsc.options
    gravity::PoissonMethod poisson = gravity::PoissonMethod::Petsc; ///< gravity.poisson
    int gradientOrder = 2;       ///< gravity.gradient_order (2 or 4)
    double p3mCutoffCells = 4.0; ///< gravity.p3m_cutoff [cells] (P3M only)
    // Node methods (occupied-cells, tree-nodes) only; the node lattice starts at the domain's
    // minimum corner:
    double gridSpacing = 0.0;    ///< gravity.grid_spacing, node distance [length] (> 0)
    double neighbourhood = -1.0; ///< gravity.neighbourhood [length] (tree-nodes; < 0: grid_spacing)
    ForceCheckSchedule check;    ///< gravity.check_every: the run's measured error
    /// A registered method's own settings (GravityMethodEntry::readKeys reads them from the
    /// scene; a program sets them itself); empty for the built-in methods.
    std::any options;
};

/// What the run summary reports about self-gravity.
struct SelfGravityStats {
    long long evaluations = 0;    ///< times the field was computed (updates)
    long long steps = 0;          ///< times the forces were applied
    double potentialEnergy = 0.0; ///< ½ Σ m φ at the last update, over all ranks [energy]
};

/// The state kept between updates besides the per-grain records (UpdatePolicy): what a
/// checkpoint stores so that a restart continues bit for bit with a threshold above 0.
struct SelfGravityState {
    long long updates = 0;        ///< field updates so far (0: the next step updates)
    double potentialEnergy = 0.0; ///< ½ Σ m φ of the last update [energy]
    long long sinceUpdate = 0;    ///< steps since the last update (gravity.update_every)
    long long interval = 0;       ///< the update interval then [steps] (0: none)
};

class SelfGravityForces {
public:
    /// Validates the options (core::InputError naming the gravity.* key, on every rank; for an
    /// unknown config.method, listing the registered ones). COLLECTIVE over `comm` (the
    /// methods duplicate it); `comm` outlives the object.
    SelfGravityForces(core::Comm const& comm, domain::BlockForest const& forest,
                      SelfGravityConfig const& config);
    ~SelfGravityForces();
    SelfGravityForces(SelfGravityForces const&) = delete;
    SelfGravityForces& operator=(SelfGravityForces const&) = delete;

    /// Adds m g to the force of every master of `local`; recomputes g first when the update
    /// policy says so (no field yet, a grain moved more than the threshold, or a grain has no
    /// record on any rank), else uses the field of the last update (extrapolated in time with
    /// gravity.update_every), which a grain that changed rank brings along. COLLECTIVE.
    void addForces(particles::LocalParticles& local);
    /// For a step whose vote of all ranks carries self-gravity's (particles::DemStep::
    /// BodyForceVote): this rank's share, from the masters of `local` after the
    /// synchronisation (gravity::UpdatePolicy::localVerdict). Not collective.
    [[nodiscard]] std::array<double, 2> voteShare(particles::LocalParticles const& local);
    /// As addForces(local), with `vote` the maximum over the ranks of every rank's
    /// voteShare() of this step, the masters unchanged since: no reduction of its own unless a
    /// grain changed rank. COLLECTIVE.
    void addForces(particles::LocalParticles& local, std::array<double, 2> const& vote);

    [[nodiscard]] SelfGravityStats const& stats() const { return m_stats; }

    /// For checkpoints: the run-wide state, and per grain (uid) its position, field and slope at
    /// the last update (nullptr if it has none, as always with update_threshold = 0 and no
    /// update_every). Not collective.
    [[nodiscard]] SelfGravityState state() const;
    [[nodiscard]] gravity::GrainRecord const* record(particles::Uid uid) const {
        return m_policy.record(uid);
    }
    /// Continues from a checkpoint: `state` and the records of any grains (this rank's slice
    /// of the file; the next addForces() brings each record to the rank holding its grain,
    /// see UpdatePolicy::due). Not collective.
    void restore(SelfGravityState const& state, std::span<particles::Uid const> uid,
                 std::span<gravity::GrainRecord const> records);

    /// For a new assignment of the blocks (a rebalance): the method starts anew on `forest`
    /// (a grid method's cells and solver; a Poisson solve then starts from zero once); the
    /// per-grain records and the statistics go on, each record brought to its grain's rank
    /// by the next addForces(). gridFields() is empty until the next update or
    /// refreshGridFields(). COLLECTIVE.
    void relocate(domain::BlockForest const& forest);

    /// The cell fields of a grid method (density, potential, acceleration of the last update)
    /// for output, or nullopt for a method without a grid or before the first update of this
    /// process (or refreshGridFields). Not collective; the same answer on every rank.
    [[nodiscard]] std::optional<gravity::GridFieldsView> gridFields() const;
    /// For the output of a restart, which has no grid fields until its next update: computes
    /// them from the grains of `local` now, leaving the forces, the per-grain records, the
    /// statistics and the next update's solve as they were (nothing if a field exists or the
    /// method has no grid). Until the next update the output then shows the field of the
    /// restored positions. COLLECTIVE.
    void refreshGridFields(particles::LocalParticles const& local);
    /// The relative error of the last update's field against the direct sum, over a sample of
    /// about `sample` grains (SampledForceError.hpp), or nullopt if the last addForces() did
    /// not update the field (the grains have moved since). COLLECTIVE.
    [[nodiscard]] std::optional<gravity::ErrorStats> sampledForceError(std::size_t sample) const;
    /// The errors measured during the run (gravity.check_every). The same on every rank.
    [[nodiscard]] ForceErrorMonitor const& measuredError() const { return m_monitor; }
    /// The update interval in steps now (gravity.update_every; 0 without one).
    [[nodiscard]] long long updateInterval() const { return m_policy.interval(); }

private:
    /// The local masters' uids, and with `state` their positions, masses and radii.
    void gather(particles::LocalParticles const& local, bool state);
    /// Whether this step reads the positions: a displacement threshold, an update, or an
    /// armed check; a step that extrapolates the field needs the uids alone.
    [[nodiscard]] bool needsState() const;
    /// addForces after the policy's verdict: updates the field if `updated`, applies it.
    void applyForces(particles::LocalParticles& local, bool updated);
    /// The grains of a step and the field the integrator gave them (a check's input).
    struct AppliedField {
        bool valid = false; ///< a step was kept (on every rank alike, also one without grains)
        std::vector<std::uint64_t> uid;
        std::vector<double> x, y, z, m, ax, ay, az;
    };

    core::Comm const* m_comm;
    SelfGravityConfig m_config; ///< reproducible: each update from the masters in uid order
    std::unique_ptr<GravityMethod> m_method;
    gravity::UpdatePolicy m_policy;
    SelfGravityStats m_stats;
    bool m_gridRefreshed = false; ///< refreshGridFields computed the grid fields
    bool m_lastUpdated = false;   ///< the last addForces() updated the field (m_ax... hold it)
    bool m_gatheredState = false; ///< the last gather() read the positions
    // The local masters, in block then storage order, or in uid order (reused between calls).
    std::vector<std::uint64_t> m_uid;
    std::vector<double> m_x, m_y, m_z, m_m, m_r, m_ax, m_ay, m_az;
    /// The field applied this step to the masters in those arrays' order (a check reads it).
    std::vector<double> m_fx, m_fy, m_fz;
    ForceErrorMonitor m_monitor;
    AppliedField m_kept; ///< the step before, while a check is armed
    /// In reproducible mode: the slot in those arrays of the k-th master in block then storage
    /// order.
    std::vector<std::uint32_t> m_slot;
    // The field of the last update per grain lives in m_policy's records (keyed by uid): it
    // follows a grain to another block or rank.
};

} // namespace regolith::coupling
