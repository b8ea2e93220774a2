#include "particles/integration/TimeStepGuard.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace regolith::particles {

namespace {

/// The particle of smallest mass of each type, among movable particles.
struct Lightest {
    double mass = std::numeric_limits<double>::infinity();
    double radius = 0.0;
    Uid uid = kInvalidUid;
};

std::vector<Lightest> lightestPerType(ParticleStorage const& ps, std::size_t numTypes) {
    std::vector<Lightest> out(numTypes);
    for (std::size_t i = 0, n = ps.size(); i < n; ++i) {
        if (ps.flags(i).isFixed())
            continue;
        std::uint32_t const t = ps.type(i);
        if (t >= numTypes)
            throw core::InputError(
                fmt::format("particle uid {} has material type {}, but only {} types are declared",
                            ps.uid(i), t, numTypes));
        Lightest& l = out[t];
        if (ps.mass(i) < l.mass || (ps.mass(i) == l.mass && ps.uid(i) < l.uid))
            l = Lightest{ps.mass(i), ps.radius(i), ps.uid(i)};
    }
    return out;
}

/// Minimises `tc(a, b)` over the pairs of present types.
template <class ContactTimeOf>
ContactTimeEstimate shortestOverTypePairs(std::vector<Lightest> const& l, ContactTimeOf&& tc) {
    ContactTimeEstimate best;
    for (std::size_t a = 0; a < l.size(); ++a) {
        if (l[a].uid == kInvalidUid)
            continue;
        for (std::size_t b = a; b < l.size(); ++b) {
            if (l[b].uid == kInvalidUid)
                continue;
            auto const [t, value] = tc(a, b);
            Lightest const& m = l[a].mass <= l[b].mass ? l[a] : l[b];
            if (t < best.contactTime || (t == best.contactTime && m.uid < best.uid)) {
                best.contactTime = t;
                best.parameterValue = value;
                best.mass = m.mass;
                best.uid = m.uid;
            }
        }
    }
    return best;
}

double pairMass(Lightest const& a, Lightest const& b) {
    return a.mass * b.mass / (a.mass + b.mass);
}

} // namespace

ContactTimeEstimate estimateContactTime(ParticleStorage const& ps, SpringDashpot const& model) {
    auto const& table = model.materials();
    auto const l = lightestPerType(ps, table.numTypes());
    auto e = shortestOverTypePairs(l, [&](std::size_t a, std::size_t b) {
        auto const& p = table(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
        return std::pair(SpringDashpot::undampedContactTime(p, pairMass(l[a], l[b])), p.stiffness);
    });
    e.parameter = "contact.stiffness";
    return e;
}

ContactTimeEstimate estimateContactTime(ParticleStorage const& ps, HertzMindlin const& model,
                                        double impactVelocity) {
    if (!(impactVelocity > 0.0) || !std::isfinite(impactVelocity))
        throw core::InputError(fmt::format(
            "the impact velocity for the Hertz contact time is {}: expected a positive finite "
            "value",
            impactVelocity));
    auto const& table = model.materials();
    auto const l = lightestPerType(ps, table.numTypes());
    auto e = shortestOverTypePairs(l, [&](std::size_t a, std::size_t b) {
        auto const& p = table(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
        double const r = l[a].radius * l[b].radius / (l[a].radius + l[b].radius);
        return std::pair(HertzMindlin::contactTime(p, pairMass(l[a], l[b]), r, impactVelocity),
                         p.effectiveYoungsModulus);
    });
    e.parameter =
        fmt::format("the effective Young's modulus (impact velocity {:.6g}) E*", impactVelocity);
    return e;
}

ContactTimeEstimate estimateContactTime(ParticleStorage const& ps, ContactLaw const& law) {
    std::size_t types = 0;
    for (std::size_t i = 0, n = ps.size(); i < n; ++i)
        types = std::max<std::size_t>(types, ps.type(i) + std::size_t{1});
    auto const l = lightestPerType(ps, types);
    auto e = shortestOverTypePairs(l, [&](std::size_t a, std::size_t b) {
        double const t = law.contactTime(static_cast<std::uint32_t>(a),
                                         static_cast<std::uint32_t>(b), pairMass(l[a], l[b]));
        return std::pair(t, t);
    });
    e.parameter = "the contact law's contactTime";
    return e;
}

ContactTimeEstimate shortestContactTime(core::Comm const& comm, ContactTimeEstimate const& local) {
    auto const tc = comm.allGather(local.contactTime);
    auto const value = comm.allGather(local.parameterValue);
    auto const mass = comm.allGather(local.mass);
    auto const uid = comm.allGather(static_cast<unsigned long long>(local.uid));
    ContactTimeEstimate best;
    best.parameter = local.parameter;
    for (std::size_t r = 0; r < tc.size(); ++r) {
        if (tc[r] < best.contactTime || (tc[r] == best.contactTime && uid[r] < best.uid)) {
            best.contactTime = tc[r];
            best.parameterValue = value[r];
            best.mass = mass[r];
            best.uid = uid[r];
        }
    }
    return best;
}

void checkTimeStep(double dt, ContactTimeEstimate const& e, bool allowUnstable) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw core::InputError(
            fmt::format("time.dt = {:.6g}: expected a positive finite value", dt));
    double const limit = e.contactTime / 10.0;
    if (dt > limit && !allowUnstable)
        throw core::InputError(fmt::format(
            "time.dt = {:.6g} exceeds t_c/10 = {:.6g} (t_c = {:.6g} from {} = {:.6g} and the "
            "smallest mass {:.6g}, uid {}); reduce time.dt or set time.allow_unstable = true",
            dt, limit, e.contactTime, e.parameter, e.parameterValue, e.mass, e.uid));
}

} // namespace regolith::particles
