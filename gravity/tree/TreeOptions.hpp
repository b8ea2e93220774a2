#pragma once
/// Parameters of the Barnes–Hut and mutual trees, with the scene keys they come from.
#include "gravity/common/PointMasses.hpp"

#include <string>

namespace regolith::gravity::tree {

/// When a cell of edge l, mass centre com (offset δ = |com - centre| from the cube's centre)
/// and b_max (largest distance from com to one of its grains) may act as a multipole on a
/// point at distance d from com: d > rcrit with
enum class OpeningCriterion {
    BmaxPlusOffset, ///< rcrit = b_max/θ + δ (default; guarded against a far centre of mass)
    Bmax,           ///< rcrit = b_max/θ (Salmon & Warren 1994, §3): cheapest at equal error
    EdgePlusOffset, ///< rcrit = l/θ + δ (Barnes 1994; the classic geometric test + guard)
};

struct TreeOptions {
    double G = kNewtonG;          ///< `gravity.G`, m³ kg⁻¹ s⁻²
    double softening = 0.0;       ///< `gravity.softening`, Plummer ε in m
    double theta = 0.5;           ///< `gravity.theta`, opening angle (dimensionless)
    bool allowLargeTheta = false; ///< `gravity.allow_large_theta`: accept θ > 1
    bool quadrupole = true;       ///< `gravity.quadrupole`: monopole + quadrupole, else monopole
    int leafSize = 8;             ///< `gravity.leaf_size`: most grains in a leaf (source side)
    int groupSize = 64;           ///< `gravity.group_size`: most targets sharing one walk
    /// `gravity.opening` = "bmax-offset" | "bmax" | "edge-offset"
    OpeningCriterion criterion = OpeningCriterion::BmaxPlusOffset;
};

/// Parses `gravity.opening`; throws core::InputError naming the key otherwise.
[[nodiscard]] OpeningCriterion parseOpeningCriterion(std::string const& name);

/// Throws core::InputError naming the key: `gravity.theta` if θ <= 0, not finite, or θ > 1
/// without allowLargeTheta (the plain criterion fails there: a cell may be accepted for a
/// grain inside it); `gravity.G`, `gravity.softening`, `gravity.leaf_size`,
/// `gravity.group_size` (>= 1) otherwise.
void validate(TreeOptions const& options);

} // namespace regolith::gravity::tree
