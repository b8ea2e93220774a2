#pragma once
// Helpers shared by the particle tests: making spheres, one DEM step of one block, and the
// measurement of a two-body collision.
#include "particles/detection/ContactDetector.hpp"
#include "particles/integration/Integrator.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>

namespace regolith::particles::test {

using core::Vec3;

inline ParticleInit sphere(Uid uid, Vec3 const& x, double radius, double mass,
                           Vec3 const& v = Vec3::Zero()) {
    ParticleInit p;
    p.uid = uid;
    p.position = x;
    p.velocity = v;
    p.radius = radius;
    p.mass = mass;
    return p;
}

inline double sphereMass(double radius, double density) {
    return density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

/// One block without neighbours: the time step of docs/design.md minus synchronisation.
template <ContactModel M, Integrator I>
class BlockStepper {
public:
    BlockStepper(ParticleStorage& ps, WallList& walls, M const& model, I integrator, double dt,
                 Vec3 gravity = Vec3::Zero())
        : m_ps(ps)
        , m_walls(walls)
        , m_model(model)
        , m_integrator(integrator)
        , m_dt(dt)
        , m_gravity(gravity) {
        computeForces(); // so that the first half kick of velocity Verlet sees them
    }

    void step() {
        m_integrator.preForce(m_ps, m_dt, m_gravity);
        computeForces();
        m_integrator.postForce(m_ps, m_dt, m_gravity);
        m_time += m_dt;
    }

    [[nodiscard]] ContactList const& contacts() const { return m_contacts; }
    [[nodiscard]] ContactDetector const& detector() const { return m_detector; }
    [[nodiscard]] double time() const { return m_time; }
    [[nodiscard]] double dt() const { return m_dt; }

private:
    void computeForces() {
        m_ps.resetForces();
        m_walls.resetForces();
        m_detector.detect(m_ps, m_walls, everywhere(), m_contacts);
        ++m_stamp;
        evaluateContacts(m_ps, m_walls, m_contacts, m_model, m_dt, m_stamp);
        pruneHistory(m_ps, m_stamp);
    }

    ParticleStorage& m_ps;
    WallList& m_walls;
    M const& m_model;
    I m_integrator;
    double m_dt;
    Vec3 m_gravity;
    ContactDetector m_detector;
    ContactList m_contacts;
    std::uint32_t m_stamp = 0;
    double m_time = 0.0;
};

/// The outcome of a head-on collision of particles 0 and 1 along x.
struct Collision {
    double restitution = 0.0;   ///< -(relative velocity after) / (relative velocity before)
    double contactTime = 0.0;   ///< from interpolated gap zero crossings [time]
    bool separated = false;     ///< the contact ended within the step budget
    std::size_t maxHistory = 0; ///< largest history size seen on particle 0 during contact
    std::size_t historyAfter = 0;
};

/// Runs `stepper` until particles 0 and 1 (touching along x) have collided and separated.
/// The contact start and end are the zero crossings of the gap |x1 - x0| - r0 - r1,
/// interpolated linearly between steps (second order in dt).
template <class Stepper>
Collision runCollision(ParticleStorage& ps, Stepper& stepper, std::size_t maxSteps) {
    auto gap = [&ps] {
        return (ps.position(1) - ps.position(0)).norm() - ps.radius(0) - ps.radius(1);
    };
    double const vBefore = (ps.velocity(1) - ps.velocity(0)).x();
    Collision c;
    double start = -1.0;
    double g0 = gap();
    for (std::size_t n = 0; n < maxSteps; ++n) {
        double const t0 = stepper.time();
        stepper.step();
        double const g1 = gap();
        if (start < 0.0 && g0 >= 0.0 && g1 < 0.0) {
            start = t0 + stepper.dt() * g0 / (g0 - g1);
        } else if (start >= 0.0 && g0 < 0.0 && g1 >= 0.0) {
            c.contactTime = t0 + stepper.dt() * g0 / (g0 - g1) - start;
            c.separated = true;
            stepper.step(); // one more step: the force-free state after separation
            break;
        }
        if (start >= 0.0)
            c.maxHistory = std::max(c.maxHistory, ps.history(0).size());
        g0 = g1;
    }
    c.restitution = -(ps.velocity(1) - ps.velocity(0)).x() / vBefore;
    c.historyAfter = ps.history(0).size();
    return c;
}

} // namespace regolith::particles::test
