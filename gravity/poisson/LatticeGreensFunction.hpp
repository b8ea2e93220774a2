#pragma once
/// The Green's function of the 7-point Laplacian on an infinite lattice of spacing
/// (h_x, h_y, h_z): g with -Δ_h g = δ_{n,0} / (h_x h_y h_z), so that the discrete potential of a
/// cell mass m at lattice offset n is -G m K(n), K = 4π g, where Newton's is -G m / |r|.
///
/// Why: the PETSc solve takes its free-space Dirichlet values from Newton's kernel, but its
/// interior follows the discrete one, which differs from 1/r by O(h² / r³) (8 % of it one cell
/// out, 1.6 % four cells out along an axis). Mass a few cells from an open face then sees a
/// boundary that does not match its own field and is pushed away from the face (FreeSpaceBoundary).
/// With K instead of 1/r for the cells near a ghost the solve reproduces the infinite lattice's
/// solution, as Hockney & Eastwood's doubled-grid method does for the continuous kernel.
///
/// How: the heat-kernel representation (continuous-time random walk on the lattice; e.g.
/// Economou, "Green's Functions in Quantum Physics", 3rd ed., sec. 5.3, and Watson's integral
/// for g(0) = 0.2527310098586632 at unit spacing)
///     g(n) = 1 / (h_x h_y h_z) ∫_0^∞ Π_a e^{-s_a} I_{n_a}(s_a) dt,   s_a = 2 t / h_a²,
/// the time integral of the lattice heat kernel. It is evaluated by the trapezoid rule in
/// u = ln t over the whole line, where the integrand is analytic and decays exponentially at
/// both ends (e^u as t -> 0, e^{-u/2} as t -> ∞), so the rule converges geometrically; the scaled
/// Bessel functions come from std::cyl_bessel_i, and from their asymptotic series for large
/// arguments. Accuracy: ~1e-14 of K (tests/gravity/grid/LatticeGreensFunctionTest.cpp).
#include "core/math/Vec3.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace regolith::gravity {

class LatticeGreensFunction {
public:
    /// Largest table radius: the asymptotic series of I_n(x) is used from x = 600 on, where it
    /// converges fast for n up to this.
    static constexpr int kMaxRadius = 24;

    /// Tabulates K for offsets |n_a| <= radius on every axis (a few milliseconds at radius 12).
    /// Throws core::Error unless every h_a > 0 and finite and 0 <= radius <= kMaxRadius.
    LatticeGreensFunction(core::Vec3 const& spacing, int radius);

    /// K(n) = 4π g(n) [1 / length]. Pre: |n_a| <= radius().
    [[nodiscard]] double kernel(std::array<std::int64_t, 3> const& n) const {
        return m_kernel[slot(n)];
    }
    /// K(n) - 1 / |r_n|: what the discrete kernel adds to Newton's at offset n != 0, ~h² / r³.
    /// Pre: |n_a| <= radius(), n != 0.
    [[nodiscard]] double correction(std::array<std::int64_t, 3> const& n) const {
        return m_correction[slot(n)];
    }
    [[nodiscard]] int radius() const { return m_radius; }
    [[nodiscard]] core::Vec3 const& spacing() const { return m_spacing; }

private:
    [[nodiscard]] std::size_t slot(std::array<std::int64_t, 3> const& n) const {
        auto const r = static_cast<std::size_t>(m_radius) + 1;
        auto const a = [](std::int64_t v) { return static_cast<std::size_t>(v < 0 ? -v : v); };
        return (a(n[2]) * r + a(n[1])) * r + a(n[0]);
    }

    core::Vec3 m_spacing;
    int m_radius = 0;
    std::vector<double> m_kernel;     ///< by |n| per axis, x fastest
    std::vector<double> m_correction; ///< the same minus Newton's (0 at n = 0)
};

} // namespace regolith::gravity
