#include "apps/spin_up/TidalFlyby.hpp"

#include <cmath>
#include <numbers>

namespace regolith::apps {

using core::Vec3;

namespace {

/// H with e sinh H - H = M (e > 1), by Newton's method from asinh(M / e) (Danby 1988,
/// Fundamentals of Celestial Mechanics, sect. 6.9): converges in a few iterations for any M.
double hyperbolicAnomaly(double meanAnomaly, double e) {
    double H = std::asinh(meanAnomaly / e);
    for (int k = 0; k < 50; ++k) {
        double const step = (e * std::sinh(H) - H - meanAnomaly) / (e * std::cosh(H) - 1.0);
        H -= step;
        if (std::abs(step) <= 1e-15 * std::max(1.0, std::abs(H)))
            break;
    }
    return H;
}

} // namespace

HyperbolicPass::HyperbolicPass(double mu, double periapsis, double eccentricity,
                               double startDistance)
    : m_mu(mu)
    , m_a(periapsis / (eccentricity - 1.0))
    , m_e(eccentricity)
    , m_n(std::sqrt(mu / (m_a * m_a * m_a))) {
    // r = a (e cosh H - 1) = startDistance before periapsis: H < 0.
    double const H0 = std::acosh((startDistance / m_a + 1.0) / m_e);
    m_periapsisTime = (m_e * std::sinh(H0) - H0) / m_n;
}

Vec3 HyperbolicPass::position(double time) const {
    double const H = hyperbolicAnomaly(m_n * (time - m_periapsisTime), m_e);
    return {m_a * (m_e - std::cosh(H)), m_a * std::sqrt(m_e * m_e - 1.0) * std::sinh(H), 0.0};
}

double HyperbolicPass::speedAtInfinity() const {
    return std::sqrt(m_mu / m_a);
}

double rocheRadius(double perturberMass, double bulkDensity) {
    return 2.44 * std::cbrt(3.0 * perturberMass / (4.0 * std::numbers::pi * bulkDensity));
}

void addTidalForce(particles::LocalParticles& grains, Vec3 const& centre, Vec3 const& perturber,
                   double gm) {
    Vec3 const toCentre = centre - perturber;
    Vec3 const frame = toCentre / std::pow(toCentre.norm(), 3);
    for (particles::BlockParticles& block : grains.blocks()) {
        particles::ParticleStorage& g = block.particles;
        g.forEachMaster([&](std::size_t i) {
            Vec3 const d = g.position(i) - perturber;
            g.force(i) -= g.mass(i) * gm * (d / std::pow(d.norm(), 3) - frame);
        });
    }
}

} // namespace regolith::apps
