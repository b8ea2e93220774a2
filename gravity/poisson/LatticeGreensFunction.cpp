#include "gravity/poisson/LatticeGreensFunction.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace regolith::gravity {

namespace {

/// Where the asymptotic series takes over from std::cyl_bessel_i (whose unscaled value
/// overflows near x = 710).
constexpr double kAsymptoticFrom = 600.0;

/// e^{-x} I_n(x) for x >= 0 (Abramowitz & Stegun 9.7.1 for large x: the first terms fall by
/// about (4n² - 1) / (8x) each, < 0.5 for n <= kMaxRadius at x >= 600).
double scaledBesselI(int n, double x) {
    if (x == 0.0)
        return n == 0 ? 1.0 : 0.0;
    if (x < kAsymptoticFrom)
        return std::cyl_bessel_i(static_cast<double>(n), x) * std::exp(-x);
    double const mu = 4.0 * n * n;
    double term = 1.0;
    double sum = 1.0;
    for (int k = 1; k < 40; ++k) {
        double const odd = 2.0 * k - 1.0;
        term *= -(mu - odd * odd) / (k * 8.0 * x);
        sum += term;
        if (std::abs(term) < 1e-17 * std::abs(sum))
            break;
    }
    return sum / std::sqrt(2.0 * std::numbers::pi * x);
}

} // namespace

LatticeGreensFunction::LatticeGreensFunction(core::Vec3 const& spacing, int radius)
    : m_spacing(spacing)
    , m_radius(radius) {
    if (!(spacing.minCoeff() > 0.0 && spacing.allFinite()))
        throw core::Error(fmt::format("LatticeGreensFunction: spacing ({}, {}, {}) not positive",
                                      spacing[0], spacing[1], spacing[2]));
    if (radius < 0 || radius > kMaxRadius)
        throw core::Error(
            fmt::format("LatticeGreensFunction: radius {} not in [0, {}]", radius, kMaxRadius));
    auto const r = static_cast<std::size_t>(radius) + 1;
    m_kernel.assign(r * r * r, 0.0);
    // Lengths in units of the smallest spacing (K scales as 1 / length).
    double const unit = spacing.minCoeff();
    core::Vec3 const h = spacing / unit;
    // The trapezoid rule in u = ln t: the integrand e^u Π_a e^{-s_a} I_{n_a}(s_a) is below
    // e^{-40} of its peak at u = -40 and falls as e^{-u/2} beyond the peak (2 e^{-31} of the
    // integral left beyond u = 62, relative to a kernel of order 1); the step 1/20 resolves it
    // far below rounding (the rule converges as e^{-π² / step} for integrands analytic in the
    // strip |Im u| < π / 2).
    constexpr double kFrom = -40.0, kTo = 62.0, kStep = 0.05;
    auto const steps = static_cast<int>(std::lround((kTo - kFrom) / kStep));
    std::vector<double> factor(3 * r);
    std::vector<double> plane(r * r);
    for (int q = 0; q <= steps; ++q) {
        double const t = std::exp(kFrom + q * kStep);
        for (std::size_t a = 0; a < 3; ++a) {
            double const s =
                2.0 * t / (h[static_cast<Eigen::Index>(a)] * h[static_cast<Eigen::Index>(a)]);
            for (std::size_t n = 0; n < r; ++n)
                factor[a * r + n] = scaledBesselI(static_cast<int>(n), s);
        }
        double const weight = t * kStep * (q == 0 || q == steps ? 0.5 : 1.0);
        for (std::size_t j = 0; j < r; ++j)
            for (std::size_t i = 0; i < r; ++i)
                plane[j * r + i] = weight * factor[r + j] * factor[i];
        for (std::size_t k = 0; k < r; ++k) {
            double const fz = factor[2 * r + k];
            double* const out = &m_kernel[k * r * r];
            for (std::size_t p = 0; p < r * r; ++p)
                out[p] += fz * plane[p];
        }
    }
    double const scale = 4.0 * std::numbers::pi / (h.prod() * unit);
    m_correction.assign(m_kernel.size(), 0.0);
    for (std::size_t k = 0; k < r; ++k)
        for (std::size_t j = 0; j < r; ++j)
            for (std::size_t i = 0; i < r; ++i) {
                std::size_t const p = (k * r + j) * r + i;
                m_kernel[p] *= scale;
                double const d = core::Vec3(static_cast<double>(i) * spacing[0],
                                            static_cast<double>(j) * spacing[1],
                                            static_cast<double>(k) * spacing[2])
                                     .norm();
                if (p != 0)
                    m_correction[p] = m_kernel[p] - 1.0 / d;
            }
}

} // namespace regolith::gravity
