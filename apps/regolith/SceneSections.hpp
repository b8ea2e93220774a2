#pragma once
/// The sections of a scene file (docs/design.md, "Scene file") as plain structs, parsed and
/// validated. [domain] is parsed by its module (domain/ForestConfig.hpp); [[particles]] and
/// [[walls]] are read straight into the particles module's types (particles::ParticleSpec,
/// particles::Wall); the other sections are parsed here until their modules (time stepping,
/// synchronisation, contacts, gravity, output) exist and take them over, so that every
/// contract key is known and typo-checked today. Units are those of the scene (SI or
/// dimensionless).
///
/// Every parse function throws core::InputError naming file, line and key; none is
/// collective (every rank parses the same scene and gets the same result or error).
#include "apps/regolith/MaterialSection.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/math/AABB.hpp"
#include "domain/Block.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/generators/GeneratorSpec.hpp"
#include "particles/generators/InsertSpec.hpp"
#include "particles/kernels/TangentialSpring.hpp"
#include "particles/storage/WallList.hpp"
#include "particles/sync/SyncMethod.hpp"

#include <any>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace regolith::apps {

enum class Integrator { Euler, Verlet };

/// [time] dt (> 0, finite, required), steps (>= 0, required), allow_unstable (default false:
/// a later stability check refuses a dt too large for the contact stiffness), integrator
/// ("euler": semi-implicit Euler, or "verlet": velocity Verlet, the default), orientation
/// (true, false or "auto", the default: integrated where something reads it, AutoChoices.hpp;
/// false: velocity Verlet leaves the grains' orientation quaternions as they are -- see
/// particles::VelocityVerlet::orientation).
struct TimeSection {
    double dt = 0.0;     ///< 0 until resolved when dtAuto
    bool dtAuto = false; ///< time.dt = "auto": from the contact and orbital times (AutoChoices)
    std::int64_t steps = 0;
    bool allowUnstable = false;
    Integrator integrator = Integrator::Verlet;
    bool orientation = true;
    bool orientationAuto = true; ///< time.orientation = "auto" (resolveSpeedChoices)
};

/// [sync] method ("nns" | "sos" | "hybrid"; default "hybrid", the scenes' default),
/// reproducible (a boolean, default false), skin (a length or "auto", the default:
/// resolveSpeedChoices): the synchronisation's own settings (particles/sync/SyncMethod.hpp);
/// subdomains ("merged", the default: each rank's blocks merged into cuboids for the
/// particles, domain/RankBoxes.hpp; "blocks": one particle subdomain per block).
struct SyncSection : particles::SyncConfig {
    bool skinAuto = true; ///< sync.skin = "auto"
    domain::Subdomains subdomains = domain::Subdomains::RankBoxes;
};

/// [contact] model (a name in the contact model registry, ContactModelRegistry.hpp:
/// "spring-dashpot", "hertz", "vdw", "dmt", or one a program registered; the model's own keys are
/// checked by its entry), the material keys when the scene has no
/// [[materials]] (stiffness, youngs_modulus, poisson_ratio, restitution, friction,
/// rolling_friction: MaterialSection.hpp; mu_r: the rolling couple is at most
/// mu_r R_eff F_n), rolling_model ("constant": model A, a constant couple that cannot hold a grain
/// at rest; "spring": model C, a spring-dashpot-slider that can, with rolling_stiffness >= 0,
/// default 2.25 mu_r^2 k_n, and rolling_damping_ratio >= 0, default 0.3; TangentialSpring.hpp),
/// initial_overlap (how far two grains may overlap at
/// the start, as a fraction of the smaller radius: 0.5 for MESA-PD's GranularGas geometry),
/// neighbour_skin (the Verlet list's skin, a length >= 0, LAMMPS's `neighbor` skin; 0: no
/// list, linked cells every step; absent: a quarter of each block's small grains' radius).
/// Defaults as in docs/guide/scene.md; initial_overlap 1e-6.
struct ContactSection {
    std::string model = "spring-dashpot";
    particles::Elasticity elasticity = particles::Elasticity::Linear; ///< the model's materials
    /// The [contact] table, whose keys the model's factory reads (none: no [contact]).
    std::optional<core::ConfigTable> table;
    particles::RollingSpring rollingSpring; ///< model C if enabled
    double initialOverlap = 1e-6;
    std::optional<double> neighbourSkin;
};

/// [gravity] external (acceleration, finite), self ("none", a method of the registry,
/// coupling::gravityMethodNames(): direct | tree | pm | p3m | occupied-cells | tree-nodes |
/// mutual-tree and those a program registered, or "auto"), the method's own keys
/// (coupling::GravityMethodEntry::readKeys), accuracy (target median relative force
/// error of "auto", default 1e-3), G > 0, theta > 0 (Barnes–Hut opening angle;
/// above 1 only with allow_large_theta = true),
/// update_threshold >= 0 (displacement that triggers a recomputation), softening >= 0 (a
/// length), [gravity.petsc] options (PETSc command-line options for the Poisson solve),
/// p3m_cutoff (cells, >= 2), grid_spacing (> 0, the node methods' node distance; the paper
/// uses 2.5 x the largest grain diameter) and neighbourhood (>= 0, tree-nodes; default
/// grid_spacing).
struct GravitySection {
    core::Vec3 external = core::Vec3::Zero();
    std::string self = "none"; ///< "none", "auto" (until AutoChoices) or a registered method
    std::any methodOptions;    ///< what the method's readKeys read (SelfGravityConfig::options)
    double G = 6.674e-11;
    double theta = 0.5;
    double updateThreshold = 0.0;
    bool thresholdAuto = false; ///< update_threshold = "auto" (AutoChoices)
    double accuracy = 1e-3;
    double softening = 0.0;
    bool allowLargeTheta = false;
    int gradientOrder = 2; ///< gravity.gradient_order of the mesh's g = -grad phi (2 or 4)
    std::string petscOptions;
    std::string poisson = "petsc"; ///< gravity.poisson: "petsc" | "fft" (mesh methods)
    double p3mCutoff = 4.0;        ///< gravity.p3m_cutoff: P3M's pair cut-off in cells (>= 2)
    double gridSpacing = 0.0;      ///< gravity.grid_spacing: node distance of the node methods
    double neighbourhood = -1.0;   ///< gravity.neighbourhood (tree-nodes); < 0: grid_spacing
    bool accuracyGiven = false;    ///< gravity.accuracy was set (the mesh methods then check it)
    /// gravity.check_every: measure the force error the grains feel after every n-th update
    /// (0: never); "auto" (the default): a check in each eighth of the run, none in a periodic
    /// domain (coupling/gravity/ForceErrorMonitor.hpp).
    std::int64_t checkEvery = 0;
    bool checkEveryAuto = true;
    /// gravity.update_every: recompute the field every n steps (besides update_threshold), the
    /// field extrapolated in time between updates; "adaptive": n follows the measured
    /// extrapolation error (gravity::UpdateInterval); 0 (absent): the threshold alone.
    std::int64_t updateEvery = 0;
    bool updateEveryAdaptive = false;
};

/// [output] dir (default "out"), vtk_every >= 0 and checkpoint_every >= 0 (steps; 0: never),
/// checkpoint_keep >= 0 (how many of the newest checkpoints this run wrote to keep; files it
/// did not write are never touched; 0: all; default 2), vtk_shadows (also write the shadow
/// copies, flagged; default false), progress_seconds (>= 0: interval of the progress lines
/// when standard output is not a terminal; 0: none; default 10), thermo_every >= 0 (steps
/// between two rows of thermo.csv and the thermo lines, ThermoLog.hpp; 0: none, the default),
/// dump_every >= 0 (steps between two particle snapshots, ParticleSnapshots.hpp; 0: none) and
/// dump_format ("csv", the default, or "hdf5").
enum class DumpFormat { Csv, Hdf5 };
struct OutputSection {
    std::string dir = "out";
    std::int64_t vtkEvery = 0;
    std::int64_t checkpointEvery = 0;
    std::int64_t checkpointKeep = 2;
    bool vtkShadows = false;
    double progressSeconds = 10.0;
    std::int64_t thermoEvery = 0;
    std::int64_t dumpEvery = 0;
    DumpFormat dumpFormat = DumpFormat::Csv;
};

/// [balance] every: steps between two measurements of the ranks' loads (the blocks' grains
/// and grid cells, coupling/balance), where the blocks are re-cut along the space-filling
/// curve when the imbalance (max / mean) exceeds `threshold` and the new cut lowers it by at
/// least half of (threshold - 1), the hysteresis; 0: the assignment of the start stays; "auto"
/// (the default): 0 on one rank, otherwise 20 measurements a run, 10 to 100 steps apart
/// (DynamicBalance.hpp). threshold >= 1, default 1.1. split_levels: how many levels below
/// the scene's forest a block may be split while the blocks are re-cut
/// (coupling/balance/BlockSplit.hpp); "auto" (the default): kAutoSplitLevels where the blocks
/// move and can split, else 0.
struct BalanceSection {
    std::int64_t every = 0;
    bool everyAuto = true;
    bool adapts = false; ///< "auto" resolved to every > 0: the interval adapts up to it
    double threshold = 1.1;
    std::int64_t splitLevels = 0;
    bool splitAuto = true;
};

/// A whole scene. `name` is the top-level `name` key, else the scene file's stem.
struct SceneDescription {
    std::string name;
    domain::ForestSpec forest;
    TimeSection time;
    SyncSection sync;
    ContactSection contact;
    MaterialsSection materials; ///< [[materials]], or [contact]'s one material
    GravitySection gravity;
    BalanceSection balance;
    /// The [[particles]] entries in scene order, checked with
    /// particles::validateParticleSpecs against [domain] (files are read only when generated).
    std::vector<particles::ParticleSpec> particles;
    std::vector<particles::Wall> walls;         ///< [[walls]] (WallSection.hpp), at time 0
    std::vector<particles::InsertSpec> inserts; ///< [[insert]] (InsertSection.hpp)
    OutputSection output;
};

[[nodiscard]] TimeSection parseTime(core::ConfigTable const& section);
[[nodiscard]] SyncSection parseSync(core::ConfigTable const& section);
[[nodiscard]] ContactSection parseContact(core::ConfigTable const& section);
[[nodiscard]] GravitySection parseGravity(core::ConfigTable const& section);
[[nodiscard]] BalanceSection parseBalance(core::ConfigTable const& section);
[[nodiscard]] OutputSection parseOutput(core::ConfigTable const& section);
/// One [[particles]] entry, read into the generators' input (particles/generators/
/// GeneratorSpec.hpp, which documents the keys). Checks what TOML decides: key names, value
/// types, choices (kind: lattice | list | agglomerate | file; lattice: sc | hcp) and integers
/// that must be non-negative (seed, type); the value rules (positive radius, region inside
/// the domain, ...) are particles::validateParticleSpecs', run by parseScene. `domain` is the
/// default lattice region; `sceneDir` is the directory a relative file path is resolved
/// against ("" for the current directory).
[[nodiscard]] particles::ParticleSpec parseParticleSource(core::ConfigTable const& entry,
                                                          core::AABB const& domain,
                                                          std::string const& sceneDir);
/// The optional key `type` of a [[particles]] or [[walls]] entry: the material index of its
/// grains or wall (contact model), an integer in [0, 2^32), default 0.
[[nodiscard]] std::uint32_t parseMaterialType(core::ConfigTable const& entry);

/// Parses every section of `root` ([domain] and [time] required, the others optional with
/// the defaults above), rejects any key that no section asked for, then validates the
/// [[particles]] entries (particles::validateParticleSpecs), whose message is prefixed with
/// where the offending key was written (locateSceneKey). `scenePath` is the file the scene
/// came from ("" for an embedded scene): it gives the default name and the directory that
/// relative particle-file paths start from.
[[nodiscard]] SceneDescription parseScene(core::ConfigTable const& root,
                                          std::string const& scenePath);

[[nodiscard]] std::string_view toString(particles::SyncMethod m);
[[nodiscard]] std::string_view toString(Integrator i);

} // namespace regolith::apps
