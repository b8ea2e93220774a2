#pragma once
/// Checks of the initial particle state, reported as core::InputError naming the uid.
#include "core/math/AABB.hpp"
#include "core/mpi/Comm.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace regolith::particles {

struct ValidationOptions {
    /// The simulation domain; a master's centre must lie in it (closed box) along every
    /// non-periodic axis.
    core::AABB domain{core::Vec3::Constant(-1e300), core::Vec3::Constant(1e300)};
    std::array<bool, 3> periodic{false, false, false};
    /// Two grains may overlap by at most this fraction of the smaller radius.
    double overlapTolerance = 1e-6;
    /// Number of declared material types; 0 skips the type check.
    std::size_t numTypes = 0;
};

/// One problem found, attributed to a uid (the smaller one for a pair).
struct ValidationIssue {
    Uid uid = kInvalidUid;
    std::string message;
};

/// The problem with the smallest uid among the particles of `ps`, if any. Per particle:
/// radius, mass and density (mass / sphere volume) zero, negative, NaN or infinite; position
/// or velocity not finite; type not below numTypes; a master outside the domain. If all
/// values are sound: pairs overlapping by more than the tolerance (pairs of two Fixed grains
/// excepted), found with ContactDetector (O(N)). Not collective.
std::optional<ValidationIssue> findInvalidParticle(ParticleStorage const& ps,
                                                   ValidationOptions const& options);

/// The message for the initial overlap of contact `c` (copies of `ps`) beyond `tolerance` of
/// the smaller radius; one that meets across a periodic face (a lattice whose period does not
/// fit the domain's extent, most often) says so.
[[nodiscard]] std::string initialOverlapMessage(ParticleStorage const& ps, Contact const& c,
                                                double tolerance);

/// Runs findInvalidParticle on every rank and, if any rank found a problem, throws on every
/// rank the same core::InputError: the problem with the smallest uid. Overlaps across blocks
/// are seen only where both grains are present (call after the first synchronisation to
/// include shadows). COLLECTIVE over `comm`.
void validateParticles(core::Comm const& comm, ParticleStorage const& ps,
                       ValidationOptions const& options);

/// Throws core::InputError "<what> = <value> (expected a positive finite value)" unless
/// `value` is positive and finite; for generators checking a scene's radius or density.
void requirePositiveFinite(double value, std::string_view what);

} // namespace regolith::particles
