#pragma once
/// The subdomains of a forest: the cuboids a rank's blocks are grouped into. For the grid
/// fields every block is its own subdomain; the particles take the rank's blocks merged into
/// as few cuboids as a greedy sweep finds, so that two blocks of one rank share no face the
/// synchronisation must cross (docs/sync.md, "Subdomains").
#include "domain/ForestBuilder.hpp"

#include <cstdint>
#include <vector>

namespace regolith::domain {

/// One subdomain: a cuboid of the lattice exactly tiled by leaves of one rank.
struct RankBox {
    LatticeBox lattice;
    int owner = 0;
    std::vector<std::uint32_t> leaves; ///< indices into the leaves, ascending (curve order)
};

/// Every leaf its own box, in curve order.
[[nodiscard]] std::vector<RankBox> oneBoxPerLeaf(std::vector<ForestLeaf> const& leaves);

/// Each rank's leaves merged into cuboids: sweeps along x, y and z join two boxes whose union
/// is a box (same extent on the other two axes, touching faces) until no sweep joins any.
/// Deterministic (every rank computes the same boxes from the same leaves); sorted by their
/// first leaf. A rank whose blocks form a cuboid (a whole domain, a Hilbert half or octant of
/// a uniform forest) gets one box. O(n log n) per sweep.
[[nodiscard]] std::vector<RankBox> mergeRankLeaves(std::vector<ForestLeaf> const& leaves);

} // namespace regolith::domain
