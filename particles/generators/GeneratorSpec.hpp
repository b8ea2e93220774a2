#pragma once
/// The `[[particles]]` entries of a scene (docs/design.md, "Scene file") as plain data: what the
/// generators in particles/generators/ take as input. The scene reader (core/config) fills
/// these structs from TOML; nothing here parses TOML. Key names in the comments are the scene
/// keys, which the generators also use in their error messages ("particles[2].spacing: ...").
#include "core/math/AABB.hpp"
#include "core/math/Vec3.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace regolith::particles {

/// `velocity = { random = [lo, hi], seed = s }`: every component uniform in [lo, hi), drawn
/// from core::random::CounterRng(seed, uid) in the order x, y, z. lo == hi gives exactly lo.
struct RandomVelocity {
    double lo = 0.0;
    double hi = 0.0;
    std::uint64_t seed = 0;
};

/// `velocity = [vx, vy, vz]` (one vector for every grain) or `velocity = { random = ... }`.
using VelocitySpec = std::variant<core::Vec3, RandomVelocity>;

/// `radius = [min, max]` (lattice) or `radius = { uniform = [min, max], seed = s }` (lattice,
/// list): each grain's radius uniform in [min, max), drawn from core::random::CounterRng(seed,
/// uid, kRadiusStream), the grain's own numbers, so the same on any number of ranks; min == max
/// gives min.
struct RadiusRange {
    /// The stream of the radius draws (the velocity's is 0: a shared seed draws both apart).
    static constexpr std::uint32_t kRadiusStream = 1;
    double min = 0.0;
    double max = 0.0;
    std::uint64_t seed = 0;
    /// The radius of the grain `uid`.
    [[nodiscard]] double draw(std::uint64_t uid) const;
};

/// `lattice = "sc"` or `"hcp"`.
enum class LatticeKind { SimpleCubic, HexagonalClosePacked };

/// `kind = "lattice"`: grains on the sites of a simple cubic or hexagonal close-packed lattice.
///
/// Sites: site (i, j, k), i, j, k >= 0, has its centre at `region.min + spacing/2 * (1,1,1)`
/// plus
///  - sc:  spacing * (i, j, k);
///  - hcp: spacing * (i + ((j + k) mod 2) / 2,  sqrt(3)/2 * (j + (k mod 2) / 3),
///                    sqrt(2/3) * k),
///    the close packing of spheres of diameter `spacing`, layers ABAB along z (Conway &
///    Sloane, "Sphere Packings, Lattices and Groups", ch. 1; the same coordinates as the
///    "Close-packing of equal spheres" article's hcp formula). On a periodic x axis the
///    shifted rows (j + k odd) start at region.min instead, x = region.min + spacing * i,
///    so that they tile across the face like the others (their site at region.max is the
///    image of the one at region.min).
/// A site is used iff, on every axis, its centre lies in [region.min, region.max) when the
/// axis is periodic, and its whole grain (centre +- radius) lies in [region.min, region.max]
/// when the axis is not: a periodic lattice tiles across the boundary, and no grain crosses a
/// wall. With spacing 1 and region [0, 80)^3 an sc lattice has exactly 80^3 sites.
struct LatticeSpec {
    LatticeKind lattice = LatticeKind::SimpleCubic; ///< `lattice`
    double spacing = 1.0;                           ///< `spacing` [length], > 0
    double radius = 0.5;                    ///< `radius` [length], > 0; with radiusRange, its max
    std::optional<RadiusRange> radiusRange; ///< `radius = [min, max]`
    double density = 1.0;                   ///< `density` [mass/length^3], > 0
    core::AABB region;                      ///< `region = { min, max }`, in the domain
    VelocitySpec velocity = core::Vec3(0.0, 0.0, 0.0); ///< `velocity`
};

/// `kind = "list"`: grains given one by one. `radius` and `velocity` hold either one value
/// for every grain or one per position; `velocity` may be empty (at rest).
struct ListSpec {
    std::vector<double> radius;             ///< `radius` [length]; with radiusRange, {its max}
    std::optional<RadiusRange> radiusRange; ///< `radius = { uniform = [min, max], seed = s }`
    std::vector<core::Vec3> position;       ///< `position`, centres inside the domain
    std::vector<core::Vec3> velocity;       ///< `velocity`, optional
    double density = 1.0;                   ///< `density`
};

/// `kind = "file"`: grains from a CSV file, one per line after a header line naming the
/// columns. Required columns x, y, z, radius; optional vx, vy, vz, wx, wy, wz (angular
/// velocity), density or mass (not both), uid, type. Missing velocity components are 0.
/// Blank lines and lines starting with '#' are skipped. The `--dump` format
/// (docs/design.md, "Dump": uid,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass) is a valid input.
struct FileSpec {
    std::string path; ///< `path`, opened as given (the scene reader resolves relative paths)
    /// The scene file's folder a relative `path` was resolved from ("": given absolute, or no
    /// scene file), named when the file cannot be opened.
    std::string resolvedFrom;
    /// `density`: used when the file has neither a density nor a mass column.
    std::optional<double> density;
};

/// `kind = "agglomerate"`: `count` grains with radii uniform in `grain_radius` packed without
/// overlap inside the sphere (center, radius) by random sequential insertion, largest first.
struct AgglomerateSpec {
    core::Vec3 center = core::Vec3::Zero();   ///< `center`
    double radius = 1.0;                      ///< `radius` of the enclosing sphere [length]
    double grainRadiusMin = 0.1;              ///< `grain_radius[0]` [length]
    double grainRadiusMax = 0.1;              ///< `grain_radius[1]` [length]
    std::int64_t count = 0;                   ///< `count`, >= 0
    core::Vec3 velocity = core::Vec3::Zero(); ///< `velocity`, the bulk velocity of all grains
    double density = 1.0;                     ///< `density`
    std::uint64_t seed = 0;                   ///< `seed`
    /// `max_attempts`: random positions tried per grain before giving up (InputError).
    std::int64_t maxAttempts = 2000;
};

/// One `[[particles]]` entry.
struct ParticleSpec {
    using Kind = std::variant<LatticeSpec, ListSpec, FileSpec, AgglomerateSpec>;
    Kind kind; ///< `kind`
    /// `type`: material index of the entry's grains (the contact model's MaterialTable).
    std::uint32_t type = 0;
    /// `angular_velocity` [rad/time]: every grain's; an agglomerate's grains also move as a
    /// rigid body turning about its center, velocity + angular_velocity x (x - center). A file
    /// with wx, wy, wz columns may not have it.
    std::optional<core::Vec3> angularVelocity;
    /// `fixed`: the grains are held in place (Flag::Fixed: never moved, still touched by
    /// others); their velocity and angular velocity must be 0.
    bool fixed = false;
};

/// The scene name of the entry's kind: "lattice", "list", "file" or "agglomerate".
[[nodiscard]] char const* kindName(ParticleSpec const& spec);

} // namespace regolith::particles
