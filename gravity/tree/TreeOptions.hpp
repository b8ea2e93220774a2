#pragma once
/// Parameters of the Barnes–Hut and mutual trees, with the scene keys they come from.
#include "gravity/common/PointMasses.hpp"

namespace regolith::gravity::tree {

struct TreeOptions {
    double G = kNewtonG;          ///< `gravity.G`, m³ kg⁻¹ s⁻²
    double softening = 0.0;       ///< `gravity.softening`, Plummer ε in m
    double theta = 0.5;           ///< `gravity.theta`, opening angle (dimensionless)
    bool allowLargeTheta = false; ///< `gravity.allow_large_theta`: accept θ > 1
    bool quadrupole = true;       ///< `gravity.quadrupole`: monopole + quadrupole, else monopole
    int leafSize = 8;             ///< `gravity.leaf_size`: most grains in a leaf (source side)
    int groupSize = 32;           ///< `gravity.group_size`: most targets sharing one walk
};

/// Throws core::InputError naming the key: `gravity.theta` if θ <= 0, not finite, or θ > 1
/// without allowLargeTheta (the plain criterion fails there: a cell may be accepted for a
/// grain inside it); `gravity.G`, `gravity.softening`, `gravity.leaf_size`,
/// `gravity.group_size` (>= 1) otherwise.
void validate(TreeOptions const& options);

} // namespace regolith::gravity::tree
