#pragma once
/// Applies a contact model to the contacts found by detection: forces and torques on both
/// partners (shadows included; reducing shadow forces to masters is the synchronisation's
/// job), history updated and stamped. Two sinks for the same per-contact code: accumulate in
/// place (evaluateContacts), or keep one ForceRecord per participant and sum them later in a
/// canonical order (evaluateContactsRecorded + sumRecords, reproducible mode).
#include "particles/detection/Contact.hpp"
#include "particles/kernels/ContactState.hpp"
#include "particles/kernels/ForceRecord.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <compare>
#include <concepts>
#include <cstdint>
#include <vector>

namespace regolith::particles {

/// The ContactState of the sphere–wall contact `c` (the wall is i, moving with its surface
/// velocity at the contact point).
ContactState wallState(ParticleStorage const& ps, WallList const& walls, WallContact const& c);

/// j's centre in i's canonical frame: position(j) + shiftJ (Contact.hpp) [length].
[[nodiscard]] inline core::Vec3 partnerCentre(ParticleStorage const& ps, Contact const& c) {
    return ps.position(c.j) + c.shiftJ;
}

/// The ContactState of the pair contact `c` (i, j in canonical order; j's lever arm taken
/// from partnerCentre). Inline: once per contact and step in the fused loop.
inline ContactState pairState(ParticleStorage const& ps, Contact const& c) {
    core::Vec3 const ri = c.point - ps.position(c.i);
    core::Vec3 const rj = c.point - partnerCentre(ps, c);
    core::Vec3 const vi = ps.velocity(c.i) + ps.angularVelocity(c.i).cross(ri);
    core::Vec3 const vj = ps.velocity(c.j) + ps.angularVelocity(c.j).cross(rj);
    double const a = ps.radius(c.i), b = ps.radius(c.j);
    return ContactState{c.normal,
                        c.penetration,
                        vj - vi,
                        ps.angularVelocity(c.j) - ps.angularVelocity(c.i),
                        1.0 / (ps.invMass(c.i) + ps.invMass(c.j)),
                        a * b / (a + b),
                        ps.invInertia(c.i) + ps.invInertia(c.j),
                        ps.type(c.i),
                        ps.type(c.j)};
}

/// Calls `f(spring, rolling)` with the contact's springs from `history`: the tangential one
/// keyed by `partner` (found through `hint`), and with `rolling` (model C) the rolling one
/// keyed by rollingKey(partner), both touched with `stamp`; without, a zero vector that is
/// not stored. Returns f's result. The rolling entry is read and written by value around f:
/// touching one entry may insert it and move the other.
template <class F>
auto withSprings(ContactHistory& history, Uid partner, std::uint32_t stamp, std::uint8_t& hint,
                 bool rolling, F&& f) {
    core::Vec3 roll = core::Vec3::Zero();
    if (!rolling)
        return f(history.touch(partner, stamp, hint).spring, roll);
    roll = history.touch(rollingKey(partner), stamp).spring;
    auto const result = f(history.touch(partner, stamp, hint).spring, roll);
    history.find(rollingKey(partner))->spring = roll;
    return result;
}

/// Something that receives one participant's share of one contact:
/// `sink(copy, partnerUid, force, torque)` with `copy` a storage index.
template <class S>
concept ContactSink = requires(S& s, std::size_t copy, Uid partner, core::Vec3 const& f,
                               core::Vec3 const& t) {
    s(copy, partner, f, t);
};

/// One pair contact of evaluateContactsWith: its spring is the history entry on i keyed by
/// uid(j), stamped `stamp` (found through `hint`, see ContactHistory::touch); `sink` receives
/// j's share (partner uid(i)), then i's (partner uid(j)). Torques use the lever arms
/// point - x_i and point - partnerCentre(j): the same bits whichever block (image) evaluates.
/// The fused Verlet loop (ContactDetector::detect with a callback) calls this as soon as it
/// finds the contact. Not collective.
template <ContactModel M, ContactSink S>
void evaluatePair(ParticleStorage& ps, Contact const& c, M const& model, double dt,
                  std::uint32_t stamp, std::uint8_t& hint, S&& sink) {
    ContactState const s = pairState(ps, c);
    ContactResponse const r =
        withSprings(ps.pairHistory(c.i), ps.uid(c.j), stamp, hint, model.hasRollingSpring(),
                    [&](auto& spring, auto& roll) { return model(s, spring, roll, dt); });
    core::Vec3 const torqueJ = (c.point - partnerCentre(ps, c)).cross(r.force) + r.torque;
    core::Vec3 const torqueI = (c.point - ps.position(c.i)).cross(r.force) + r.torque;
    sink(c.j, ps.uid(c.i), r.force, torqueJ);
    sink(c.i, ps.uid(c.j), core::Vec3(-r.force), core::Vec3(-torqueI));
}

/// The sphere-wall half of evaluateContactsWith. Not collective.
template <ContactModel M, ContactSink S>
void evaluateWallsWith(ParticleStorage& ps, WallList& walls, std::vector<WallContact> const& list,
                       M const& model, double dt, std::uint32_t stamp, S&& sink) {
    for (WallContact const& c : list) {
        ContactState const s = wallState(ps, walls, c);
        Uid const wall = walls[c.wall].uid;
        std::uint8_t hint = 0;
        ContactResponse const r =
            withSprings(ps.history(c.particle), wall, stamp, hint, model.hasRollingSpring(),
                        [&](auto& spring, auto& roll) { return model(s, spring, roll, dt); });
        sink(c.particle, wall, r.force,
             core::Vec3((c.point - ps.position(c.particle)).cross(r.force) + r.torque));
        walls.addReaction(c.wall, c.point, r.force, r.torque);
    }
}

/// The per-contact code both evaluations share: evaluates every contact of `contacts` with
/// `model` and hands each participant's force and torque to `sink` -- for a pair first j's
/// (partner uid(i)), then i's (partner uid(j)); for a wall contact the sphere's (partner the
/// wall's uid) -- and adds the opposite to the wall's load (WallList::addReaction). A pair's
/// tangential spring is the history entry on i keyed by uid(j); a wall contact's is on the sphere
/// keyed by the wall's uid. Every entry used is stamped with `stamp`, so that `pruneHistory(ps,
/// stamp)` afterwards drops the contacts that broke. Not collective.
template <ContactModel M, ContactSink S>
void evaluateContactsWith(ParticleStorage& ps, WallList& walls, ContactList const& contacts,
                          M const& model, double dt, std::uint32_t stamp, S&& sink) {
    for (Contact const& c : contacts.pairs) {
        std::uint8_t hint = 0;
        evaluatePair(ps, c, model, dt, stamp, hint, sink);
    }
    evaluateWallsWith(ps, walls, contacts.walls, model, dt, stamp, sink);
}

/// Evaluates `contacts` (see evaluateContactsWith) and adds the forces and torques to
/// `ps.force` / `ps.torque` in contact order. Forces are accumulated: reset them before.
/// Not collective.
template <ContactModel M>
void evaluateContacts(ParticleStorage& ps, WallList& walls, ContactList const& contacts,
                      M const& model, double dt, std::uint32_t stamp) {
    evaluateContactsWith(ps, walls, contacts, model, dt, stamp,
                         [&ps](std::size_t k, Uid, core::Vec3 const& f, core::Vec3 const& t) {
                             ps.force(k) += f;
                             ps.torque(k) += t;
                         });
}

/// Evaluates `contacts` like evaluateContacts (history touched and stamped, wall reactions
/// accumulated) but leaves ps.force / ps.torque alone and appends one ForceRecord per
/// participant to `out`: two per pair (on i with partner uid(j), on j with partner uid(i)),
/// one per wall contact (partner = the wall's uid). Sum them with sumRecords (one block) or
/// send shadows' records to their masters (ParticleSync's reproducible reduceForces).
/// Not collective.
template <ContactModel M>
void evaluateContactsRecorded(ParticleStorage& ps, WallList& walls, ContactList const& contacts,
                              M const& model, double dt, std::uint32_t stamp,
                              std::vector<ForceRecord>& out) {
    out.reserve(out.size() + 2 * contacts.pairs.size() + contacts.walls.size());
    evaluateContactsWith(
        ps, walls, contacts, model, dt, stamp,
        [&out](std::size_t k, Uid partner, core::Vec3 const& f, core::Vec3 const& t) {
            out.push_back(ForceRecord{k, partner, f, t});
        });
}

/// Anything that is one contribution to one body's force: a partner uid, a force and a torque
/// (ForceRecord, or the synchronisation's records of shadows sent to a master).
template <class R>
concept PartnerShare = requires(R const& r) {
    { r.partner } -> std::convertible_to<Uid>;
    { r.force } -> std::convertible_to<core::Vec3>;
    { r.torque } -> std::convertible_to<core::Vec3>;
};

/// Total order of the contributions to ONE body, the order in which a reproducible sum adds
/// them: ascending partner uid; ties (a pair touching through several periodic images, so the
/// same partner twice) by the IEEE total order of force, then torque components, so that the
/// order -- hence the sum -- depends only on the set of contributions, never on where they
/// came from or in which order they arrived.
template <PartnerShare A, PartnerShare B>
[[nodiscard]] bool partnerOrder(A const& a, B const& b) {
    if (a.partner != b.partner)
        return a.partner < b.partner;
    auto compare = [](core::Vec3 const& x, core::Vec3 const& y) {
        for (int d = 0; d < 3; ++d)
            if (auto const o = std::strong_order(x[d], y[d]); o != 0)
                return o;
        return std::strong_ordering::equal;
    };
    if (auto const o = compare(a.force, b.force); o != 0)
        return o < 0;
    return compare(a.torque, b.torque) < 0;
}

/// Order of the records of one storage for sumRecords: by (uid(copy), image(copy)), then
/// partnerOrder. Pre: a.copy, b.copy < ps.size().
[[nodiscard]] bool recordOrder(ParticleStorage const& ps, ForceRecord const& a,
                               ForceRecord const& b);

/// Sorts `records` with recordOrder and adds them, in that order, to ps.force / ps.torque of
/// their copies. Every copy therefore receives its contributions in ascending partner uid,
/// whatever the order of the contact list; reset forces first to sum from zero. Not collective.
void sumRecords(std::vector<ForceRecord>& records, ParticleStorage& ps);

/// Drops, on every particle, the history entries not stamped with `stamp` (contacts that
/// were not evaluated in that pass have broken). Not collective.
void pruneHistory(ParticleStorage& ps, std::uint32_t stamp);

/// Elastic energy stored in the overlaps of `contacts` for a linear spring of stiffness
/// `stiffness(typeI, typeJ)`: sum of k delta^2 / 2 (energy checks in tests and runs).
template <class StiffnessOf>
double elasticEnergy(ParticleStorage const& ps, WallList const& walls, ContactList const& contacts,
                     StiffnessOf&& stiffness) {
    double e = 0.0;
    for (Contact const& c : contacts.pairs)
        e += 0.5 * stiffness(ps.type(c.i), ps.type(c.j)) * c.penetration * c.penetration;
    for (WallContact const& c : contacts.walls)
        e += 0.5 * stiffness(walls[c.wall].type, ps.type(c.particle)) * c.penetration *
             c.penetration;
    return e;
}

} // namespace regolith::particles
