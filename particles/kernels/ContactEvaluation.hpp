#pragma once
/// Applies a contact model to the contacts found by detection: forces and torques on both
/// partners (shadows included; reducing shadow forces to masters is the synchronisation's
/// job), history updated and stamped.
#include "particles/detection/Contact.hpp"
#include "particles/kernels/ContactState.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <cstdint>

namespace regolith::particles {

/// The ContactState of the pair contact `c` (i, j in canonical order).
ContactState pairState(ParticleStorage const& ps, Contact const& c);
/// The ContactState of the sphere–wall contact `c` (the wall is i).
ContactState wallState(ParticleStorage const& ps, WallList const& walls, WallContact const& c);

/// Evaluates every contact of `contacts` with `model` and adds the forces and torques to
/// `ps` (and the reaction on each wall to `walls.force`). A pair's tangential spring is the
/// history entry on i keyed by uid(j); a wall contact's is on the sphere keyed by the wall's
/// uid. Every entry used is stamped with `stamp`, so that `pruneHistory(ps, stamp)` afterwards
/// drops the contacts that broke. Forces are accumulated: reset them before. Not collective.
template <ContactModel M>
void evaluateContacts(ParticleStorage& ps, WallList& walls, ContactList const& contacts,
                      M const& model, double dt, std::uint32_t stamp) {
    for (Contact const& c : contacts.pairs) {
        ContactState const s = pairState(ps, c);
        core::Vec3& spring = ps.history(c.i).touch(ps.uid(c.j), stamp).spring;
        ContactResponse const r = model(s, spring, dt);
        ps.force(c.j) += r.force;
        ps.force(c.i) -= r.force;
        ps.torque(c.j) += (c.point - ps.position(c.j)).cross(r.force) + r.torque;
        ps.torque(c.i) -= (c.point - ps.position(c.i)).cross(r.force) + r.torque;
    }
    for (WallContact const& c : contacts.walls) {
        ContactState const s = wallState(ps, walls, c);
        core::Vec3& spring = ps.history(c.particle).touch(walls[c.wall].uid, stamp).spring;
        ContactResponse const r = model(s, spring, dt);
        ps.force(c.particle) += r.force;
        ps.torque(c.particle) += (c.point - ps.position(c.particle)).cross(r.force) + r.torque;
        walls.force(c.wall) -= r.force;
    }
}

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
