#include "particles/validation/ParticleValidation.hpp"

#include "core/Error.hpp"
#include "particles/detection/ContactDetector.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace regolith::particles {

namespace {

bool positiveFinite(double v) {
    return v > 0.0 && std::isfinite(v);
}

std::string vec(core::Vec3 const& v) {
    return fmt::format("({:.6g}, {:.6g}, {:.6g})", v.x(), v.y(), v.z());
}

/// The first problem of particle i alone, or an empty string.
std::string checkOne(ParticleStorage const& ps, std::size_t i, ValidationOptions const& o) {
    Uid const uid = ps.uid(i);
    double const r = ps.radius(i), m = ps.mass(i);
    if (!positiveFinite(r))
        return fmt::format("particle uid {}: radius = {} (expected a positive finite value)", uid,
                           r);
    if (!positiveFinite(m))
        return fmt::format("particle uid {}: mass = {} (expected a positive finite value)", uid, m);
    double const density = m / (4.0 / 3.0 * std::numbers::pi * r * r * r);
    if (!positiveFinite(density))
        return fmt::format("particle uid {}: density = {} (mass {} over the volume of radius "
                           "{}; expected a positive finite value)",
                           uid, density, m, r);
    if (!ps.position(i).allFinite())
        return fmt::format("particle uid {}: position {} is not finite", uid, vec(ps.position(i)));
    if (!ps.velocity(i).allFinite() || !ps.angularVelocity(i).allFinite())
        return fmt::format("particle uid {}: velocity {} or angular velocity {} is not finite", uid,
                           vec(ps.velocity(i)), vec(ps.angularVelocity(i)));
    if (o.numTypes > 0 && ps.type(i) >= o.numTypes)
        return fmt::format("particle uid {}: material type {} is not below the {} declared types",
                           uid, ps.type(i), o.numTypes);
    if (ps.flags(i).isMaster()) {
        static constexpr char kAxis[] = {'x', 'y', 'z'};
        for (int d = 0; d < 3; ++d) {
            if (o.periodic[static_cast<std::size_t>(d)])
                continue;
            double const x = ps.position(i)[d];
            if (x < o.domain.min[d] || x > o.domain.max[d])
                return fmt::format("particle uid {} at {} is outside the domain {} - {} along "
                                   "the non-periodic axis {}",
                                   uid, vec(ps.position(i)), vec(o.domain.min), vec(o.domain.max),
                                   kAxis[d]);
        }
    }
    return {};
}

} // namespace

std::optional<ValidationIssue> findInvalidParticle(ParticleStorage const& ps,
                                                   ValidationOptions const& options) {
    std::optional<ValidationIssue> best;
    auto consider = [&best](Uid uid, std::string message) {
        if (!best || uid < best->uid)
            best = ValidationIssue{uid, std::move(message)};
    };
    for (std::size_t i = 0, n = ps.size(); i < n; ++i)
        if (auto msg = checkOne(ps, i, options); !msg.empty())
            consider(ps.uid(i), std::move(msg));
    if (best || ps.empty())
        return best; // overlaps need sound radii and positions

    ContactDetector detector;
    ContactList contacts;
    detector.detect(ps, WallList{}, everywhere(), contacts);
    for (Contact const& c : contacts.pairs) {
        double const rMin = std::min(ps.radius(c.i), ps.radius(c.j));
        if (c.penetration > options.overlapTolerance * rMin)
            consider(ps.uid(c.i), initialOverlapMessage(ps, c, options.overlapTolerance));
    }
    return best;
}

std::string initialOverlapMessage(ParticleStorage const& ps, Contact const& c, double tolerance) {
    double const rMin = std::min(ps.radius(c.i), ps.radius(c.j));
    std::string across;
    for (int a = 0; a < 3; ++a)
        if (c.shiftJ[a] != 0.0)
            across += std::string(across.empty() ? "" : ", ") + "xyz"[a];
    if (!across.empty())
        across = fmt::format(", across the periodic face of {} (grains placed up to the face "
                             "meet those on the other side: e.g. a lattice whose period does not "
                             "fit the domain's extent there; make the extent a multiple of it)",
                             across);
    return fmt::format("particles uid {} and uid {} overlap by {:.6g} (more than {:g} of the "
                       "smaller radius {:.6g}){}; initial grains must not overlap (or raise "
                       "contact.initial_overlap)",
                       ps.uid(c.i), ps.uid(c.j), c.penetration, tolerance, rMin, across);
}

void validateParticles(core::Comm const& comm, ParticleStorage const& ps,
                       ValidationOptions const& options) {
    auto const local = findInvalidParticle(ps, options);
    auto const uids =
        comm.allGather(static_cast<unsigned long long>(local ? local->uid : kInvalidUid));
    int root = -1;
    unsigned long long bestUid = kInvalidUid;
    for (std::size_t r = 0; r < uids.size(); ++r)
        if (uids[r] != kInvalidUid && (root < 0 || uids[r] < bestUid)) {
            root = static_cast<int>(r);
            bestUid = uids[r];
        }
    if (root < 0)
        return;
    std::string message = comm.rank() == root ? local->message : std::string{};
    comm.broadcast(message, root);
    throw core::InputError(message);
}

void requirePositiveFinite(double value, std::string_view what) {
    if (!positiveFinite(value))
        throw core::InputError(
            fmt::format("{} = {} (expected a positive finite value)", what, value));
}

} // namespace regolith::particles
