#pragma once
/// The data every self-gravity kernel works on: point masses in SoA spans (positions in m,
/// masses in kg, optional radii in m) and the field written back (accelerations in m/s²,
/// potential in m²/s²). Gravity never sees the particle storage (docs/design.md, "Layers"): the
/// caller hands spans of its masters, so a kernel test needs no particles and no forest.
#include <cstddef>
#include <span>

namespace regolith::gravity {

/// Newton's constant in m³ kg⁻¹ s⁻² (CODATA 2018), the default of `gravity.G`.
inline constexpr double kNewtonG = 6.674e-11;

/// Sources (and targets): n point masses. `r` is empty or holds n radii (used by the grid
/// baselines for the field inside a grain).
struct PointMasses {
    std::span<double const> x, y, z, m;
    std::span<double const> r = {};

    [[nodiscard]] std::size_t size() const { return x.size(); }
};

/// Where a kernel writes: n accelerations and, if `phi` is not empty, n potentials.
/// Kernels overwrite (not add to) these arrays.
struct FieldOut {
    std::span<double> ax, ay, az;
    std::span<double> phi = {};

    [[nodiscard]] std::size_t size() const { return ax.size(); }
};

/// Throws core::InputError if the spans of `masses` differ in length, a mass is negative or
/// not finite, or a position is not finite; the message names `key` (e.g. "gravity") and the
/// first offending index. Not collective: a caller that validates on every rank must agree
/// on the outcome itself (Comm::allTrue) before the next collective.
void validatePointMasses(PointMasses const& masses, char const* key);

/// Throws core::Error if `out` does not hold `n` entries in ax, ay, az (and phi, if given).
void validateFieldOut(FieldOut const& out, std::size_t n);

} // namespace regolith::gravity

namespace regolith::core {
class Comm;
}

namespace regolith::gravity {

/// validatePointMasses on every rank, agreed (core::agreeOnInputError). COLLECTIVE over
/// `comm`.
void validatePointMassesCollective(core::Comm const& comm, PointMasses const& masses,
                                   char const* key);

} // namespace regolith::gravity
