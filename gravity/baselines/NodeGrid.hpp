#pragma once
/// The overlay grid of nodes of the second paper (Nesmachnow, Rocchetti & Tancredi, §3):
/// accelerations are computed at grid nodes and interpolated trilinearly to the grains.
/// Only the nodes around occupied cells are used (§4.1), with the paper's 64-node expansion
/// (the 4×4×4 nodes around a grain's cell) so that a grain that moves into a neighbouring
/// cell between updates still finds up-to-date nodes.
#include "core/math/Vec3.hpp"
#include "gravity/common/PointMasses.hpp"

#include <cstdint>
#include <vector>

namespace regolith::gravity::baselines {

struct NodeGrid {
    core::Vec3 origin = core::Vec3::Zero(); ///< a node, m
    double spacing = 1.0;                   ///< node distance h, m (the paper: 2.5 × the
                                            ///< largest grain diameter)
};

/// Nodes (as packed 64-bit keys, ascending, unique) around the cells of `grains`: the 8
/// corners of each occupied cell, or the 64 nodes of the expansion if `expand64`. Not
/// collective.
[[nodiscard]] std::vector<std::uint64_t> nodesAround(NodeGrid const& grid,
                                                     PointMasses const& grains, bool expand64);

/// Position (m) of the node with key `key`.
[[nodiscard]] core::Vec3 nodePosition(NodeGrid const& grid, std::uint64_t key);

/// Node values: acceleration and potential per node, in the order of `keys`.
struct NodeField {
    std::vector<std::uint64_t> keys;
    std::vector<double> ax, ay, az, phi;
};

/// Trilinear interpolation of `nodes` to `targets` (the 8 corners of each target's cell
/// must be in `nodes`, else core::Error), minus each target's own field (accumulateSphereField
/// with constant `G`) at those corners interpolated with the same weights: the nodes hold the
/// field of every grain, the target's included, and interpolated it does not vanish at the
/// grain (a lone grain 0.3 spacings from a node accelerated itself at ~G m / h², and its
/// potential energy held a self part that changed as it moved). Overwrites `out`. Returns
/// ½ Σ m φ. Not collective.
double interpolateToGrains(NodeGrid const& grid, NodeField const& nodes, PointMasses const& targets,
                           double G, FieldOut out);

/// Adds to points [0, n) the field of sources of finite radius (uniform spheres): outside a
/// grain the point-mass law, inside it the linear interior field a = G m d / r³ and
/// φ = -G m (3 r² - d²) / (2 r³). A point at zero distance from a source of radius 0 is
/// skipped. Inner loop over points (vectorisable). Not collective.
void accumulateSphereField(double const* px, double const* py, double const* pz, std::size_t n,
                           PointMasses const& sources, std::size_t begin, std::size_t end, double G,
                           double* ax, double* ay, double* az, double* phi);

/// Throws core::InputError naming `gravity.grid_spacing` if the spacing is not > 0.
void validate(NodeGrid const& grid);

} // namespace regolith::gravity::baselines
