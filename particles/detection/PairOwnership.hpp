#pragma once
/// Settling the contact-point rule (ContactDetector's class comment) once per listed pair
/// instead of once per pair and step: while a Verlet list holds, no copy moves skin / 2 from
/// its reference position, so a pair's ownership point stays in a small ball around the pair's
/// reference midpoint. If that ball lies well inside the block's share of the domain, the block
/// evaluates the pair whenever it overlaps; if it lies well outside, never. Only the pairs
/// whose ball straddles a block or domain face need the rule every step.
#include "core/math/AABB.hpp"
#include "core/math/Vec3.hpp"
#include "particles/detection/PeriodicFrame.hpp"

namespace regolith::particles {

enum class Settled {
    Never,  ///< another block or image instance evaluates the pair, whatever happens
    Always, ///< this block evaluates it whenever the two overlap
    Open,   ///< the rule must decide every step
};

/// The bound on the ownership point q of a pair i, j (radii ri, rj) over a list's life, from
/// the midpoint m of the two centres: |q - m| <= |ri - rj| / 2 at any time (q is the contact
/// point m + (ri - rj)/2 n, or, once the overlap reaches the smaller diameter, the smaller
/// centre, at distance |x_j - x_i| / 2 <= |ri - rj| / 2 from m), and m moves less than skin / 2
/// (each centre less than skin / 2). Plus `rounding` [length], which must cover the rounding of q,
/// m and the periodic wrap.
[[nodiscard]] inline double ownershipReach(double ri, double rj, double skin, double rounding) {
    double const dr = ri > rj ? ri - rj : rj - ri;
    return 0.5 * skin + 0.5 * dr + rounding;
}

/// Where the contact-point rule emits a pair whose ownership point lies there: `region`, and on
/// a periodic axis of `frame` the domain too (a point outside it wraps to another image:
/// ContactDetector's `image(i) == -o`); anywhere along a wrapped axis (one instance).
[[nodiscard]] core::AABB emittingBox(core::AABB const& region, PeriodicFrame const& frame);

/// Settles the rule for a pair whose reference midpoint, in the frame of the copy of i the
/// block holds (its local position), is `mid`, and whose ownership point stays within `reach`
/// of it (ownershipReach). `region` is the block's evaluation region, `frame` the detection's
/// periodic frame: the rule emits the pair iff the ownership point, seen from the block's copy
/// of i, lies in the region and in the domain on every periodic axis. Not collective.
[[nodiscard]] Settled settleOwnership(core::Vec3 const& mid, double reach, core::AABB const& region,
                                      PeriodicFrame const& frame);

} // namespace regolith::particles
