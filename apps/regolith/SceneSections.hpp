#pragma once
/// The sections of a scene file (DESIGN.md, "Scene file") as plain structs, parsed and
/// validated. [domain] is parsed by its module (domain/ForestConfig.hpp); the other sections
/// are parsed here until their modules (time stepping, synchronisation, contacts, gravity,
/// particle generators, walls, output) exist and take them over, so that every contract key
/// is known and typo-checked today. Units are those of the scene (SI or dimensionless).
///
/// Every parse function throws core::InputError naming file, line and key; none is
/// collective (every rank parses the same scene and gets the same result or error).
#include "core/config/ConfigTable.hpp"
#include "core/math/AABB.hpp"
#include "domain/ForestSpec.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace regolith::apps {

enum class Integrator { Euler, Verlet };

/// [time] dt (> 0, finite, required), steps (>= 0, required), allow_unstable (default false:
/// a later stability check refuses a dt too large for the contact stiffness), integrator
/// ("euler": semi-implicit Euler, or "verlet": velocity Verlet, the default).
struct TimeSection {
    double dt = 0.0;
    std::int64_t steps = 0;
    bool allowUnstable = false;
    Integrator integrator = Integrator::Verlet;
};

enum class SyncMethod { Nns, Sos, Hybrid };

/// [sync] method ("nns" | "sos" | "hybrid", default "sos"), reproducible (default false).
struct SyncSection {
    SyncMethod method = SyncMethod::Sos;
    bool reproducible = false;
};

enum class ContactModel { SpringDashpot, Hertz };

/// [contact] model ("spring-dashpot" | "hertz"), stiffness (> 0; N/m for spring-dashpot,
/// the effective modulus in Pa for Hertz), restitution in [0, 1], friction >= 0 (Coulomb
/// coefficient), rolling_friction >= 0. Defaults as in DESIGN.md: 1e4, 0.9, 0.5, 0.
struct ContactSection {
    ContactModel model = ContactModel::SpringDashpot;
    double stiffness = 1e4;
    double restitution = 0.9;
    double friction = 0.5;
    double rollingFriction = 0.0;
};

enum class SelfGravity { None, Direct, Tree, Pm, P3m, OccupiedCells, TreeNodes };

/// [gravity] external (acceleration, finite), self (none | direct | tree | pm | p3m |
/// occupied-cells | tree-nodes), G > 0, theta > 0 (Barnes–Hut opening angle),
/// update_threshold >= 0 (displacement that triggers a recomputation), softening >= 0 (a
/// length), [gravity.petsc] options (PETSc command-line options for the Poisson solve).
struct GravitySection {
    core::Vec3 external = core::Vec3::Zero();
    SelfGravity self = SelfGravity::None;
    double G = 6.674e-11;
    double theta = 0.5;
    double updateThreshold = 0.0;
    double softening = 0.0;
    std::string petscOptions;
};

/// An initial velocity: every component is mean + a uniform random number in
/// [randomMin, randomMax], to be drawn from a counter-based generator keyed by (seed, uid).
/// Written `velocity = [vx, vy, vz]` or `velocity = { mean = [..], random = [lo, hi],
/// seed = n }` (every key of the table optional).
struct VelocitySpec {
    core::Vec3 mean = core::Vec3::Zero();
    double randomMin = 0.0;
    double randomMax = 0.0;
    std::uint64_t seed = 0;
};

enum class LatticeKind { Sc, Bcc, Fcc, Hcp };

/// kind = "lattice": grains on a lattice filling `region` (default: the whole domain).
/// `spacing` is the nearest-neighbour distance of the lattice (so hcp with spacing 1 and
/// radius 0.5 is a touching close packing); 2 * radius <= spacing.
struct LatticeSource {
    LatticeKind lattice = LatticeKind::Sc;
    double spacing = 1.0;
    double radius = 0.5;
    double density = 1.0;
    core::AABB region;
    VelocitySpec velocity;
};

/// kind = "list": explicit grains. `radius` is one number for all or one per grain;
/// `velocity` (optional) one per grain.
struct ListSource {
    std::vector<double> radius;
    std::vector<core::Vec3> position;
    std::vector<core::Vec3> velocity;
    double density = 1.0;
};

/// kind = "agglomerate": `count` grains with radii uniform in [grainRadiusMin,
/// grainRadiusMax] packed into a sphere of `radius` around `center` (placement from `seed`).
struct AgglomerateSource {
    core::Vec3 center = core::Vec3::Zero();
    double radius = 1.0;
    double grainRadiusMin = 0.1;
    double grainRadiusMax = 0.1;
    std::int64_t count = 1;
    VelocitySpec velocity;
    double density = 1.0;
    std::uint64_t seed = 0;
};

/// kind = "file": grains read from a CSV file (the --dump format). `path` as written;
/// `resolvedPath` relative to the scene file's directory.
struct FileSource {
    std::string path;
    std::string resolvedPath;
};

using ParticleSource = std::variant<LatticeSource, ListSource, AgglomerateSource, FileSource>;

/// [[walls]] an infinite plane through `point`; `normal` (unit length after parsing) points
/// into the half-space where the grains are.
struct WallSpec {
    core::Vec3 point = core::Vec3::Zero();
    core::Vec3 normal = core::Vec3::UnitZ();
};

/// [output] dir (default "out"), vtk_every >= 0 and checkpoint_every >= 0 (steps; 0: never).
struct OutputSection {
    std::string dir = "out";
    std::int64_t vtkEvery = 0;
    std::int64_t checkpointEvery = 0;
};

/// A whole scene. `name` is the top-level `name` key, else the scene file's stem.
struct SceneDescription {
    std::string name;
    domain::ForestSpec forest;
    TimeSection time;
    SyncSection sync;
    ContactSection contact;
    GravitySection gravity;
    std::vector<ParticleSource> particles;
    std::vector<WallSpec> walls;
    OutputSection output;
};

[[nodiscard]] TimeSection parseTime(core::ConfigTable const& section);
[[nodiscard]] SyncSection parseSync(core::ConfigTable const& section);
[[nodiscard]] ContactSection parseContact(core::ConfigTable const& section);
[[nodiscard]] GravitySection parseGravity(core::ConfigTable const& section);
[[nodiscard]] WallSpec parseWall(core::ConfigTable const& entry);
[[nodiscard]] OutputSection parseOutput(core::ConfigTable const& section);
/// One [[particles]] entry. `domain` is the default lattice region; `sceneDir` the directory
/// relative paths are resolved against ("" for the current directory).
[[nodiscard]] ParticleSource parseParticleSource(core::ConfigTable const& entry,
                                                 core::AABB const& domain,
                                                 std::string const& sceneDir);

/// Parses every section of `root` ([domain] and [time] required, the others optional with
/// the defaults above), then rejects any key that no section asked for. `scenePath` is the
/// file the scene came from ("" for an embedded scene): it gives the default name and the
/// directory that relative particle-file paths start from.
[[nodiscard]] SceneDescription parseScene(core::ConfigTable const& root,
                                          std::string const& scenePath);

[[nodiscard]] std::string_view toString(SyncMethod m);
[[nodiscard]] std::string_view toString(ContactModel m);
[[nodiscard]] std::string_view toString(SelfGravity g);
[[nodiscard]] std::string_view toString(LatticeKind k);
[[nodiscard]] std::string_view toString(Integrator i);

} // namespace regolith::apps
