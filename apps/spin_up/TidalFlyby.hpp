#pragma once
/// A tidal fly-by: a point mass M passing the pile on a hyperbola, as an external field in the
/// frame falling with the pile's centre c. A grain at x feels the perturber's pull minus the
/// pull at c (the frame's own acceleration), the tidal acceleration
///     a(x) = -G M [ (x - X) / |x - X|^3 - (c - X) / |c - X|^3 ],
/// X the perturber's position (e.g. Richardson, Bottke & Love 1998, Icarus 134, 47: rubble
/// piles passing the Earth). The pile stays near c; its own response (the pull on M) and the
/// third-order shift of its centre are neglected.
#include "core/math/Vec3.hpp"
#include "particles/sync/BlockParticles.hpp"

namespace regolith::apps {

/// The perturber's position relative to the pile on a hyperbola in the x-y plane, periapsis
/// on +x at mid-pass, moving towards +y: with a = q / (e - 1) and n = sqrt(mu / a^3), the
/// hyperbolic anomaly H solves n (t - t_p) = e sinh H - H and X = a (e - cosh H),
/// Y = a sqrt(e^2 - 1) sinh H (Murray & Dermott 1999, Solar System Dynamics, sect. 2.5).
/// Time 0 is where it is `startDistance` away, approaching; `duration()` later it is as far,
/// receding.
class HyperbolicPass {
public:
    /// mu = G (M + pile mass); q, startDistance > q: lengths; e > 1. Not checked here.
    HyperbolicPass(double mu, double periapsis, double eccentricity, double startDistance);
    [[nodiscard]] core::Vec3 position(double time) const;
    [[nodiscard]] double duration() const { return 2.0 * m_periapsisTime; }
    [[nodiscard]] double speedAtInfinity() const;

private:
    double m_mu, m_a, m_e, m_n, m_periapsisTime;
};

/// The Roche radius of a fluid body of density rho around a point mass M:
/// 2.44 (3 M / (4 pi rho))^(1/3) (Chandrasekhar 1969, Ellipsoidal Figures of Equilibrium,
/// ch. 8; rubble piles with friction survive somewhat closer, Sharma 2009, Icarus 200, 636).
[[nodiscard]] double rocheRadius(double perturberMass, double bulkDensity);

/// Adds the tidal force m_i a(x_i) of a point mass with G M = `gm` at `perturber` (world
/// coordinates) on a frame centred at `centre` to every master. Not collective.
void addTidalForce(particles::LocalParticles& grains, core::Vec3 const& centre,
                   core::Vec3 const& perturber, double gm);

} // namespace regolith::apps
