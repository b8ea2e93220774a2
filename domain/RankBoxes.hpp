#pragma once
/// The subdomains of a forest: the cuboids a rank's blocks are grouped into. For the grid
/// fields every block is its own subdomain; the particles take the rank's blocks merged into
/// as few cuboids as a greedy sweep finds, so that two blocks of one rank share no face the
/// synchronisation must cross (docs/sync.md, "Subdomains").
#include "domain/ForestBuilder.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace regolith::domain {

/// One subdomain: a cuboid of the lattice exactly tiled by leaves of one rank, those of
/// SubdomainCut::leaves[begin, end).
struct RankBox {
    LatticeBox lattice;
    int owner = 0;
    std::uint32_t begin = 0;
    std::uint32_t end = 0;
};

/// A cut of the forest's leaves into subdomains: the boxes sorted by their first leaf, and the
/// leaves of each box ascending (curve order), box after box (4 bytes a leaf, no allocation
/// per box: every rank cuts the whole forest).
struct SubdomainCut {
    std::vector<RankBox> boxes;
    std::vector<std::uint32_t> leaves; ///< indices into the forest's leaves

    [[nodiscard]] std::span<std::uint32_t const> leavesOf(RankBox const& box) const {
        return {leaves.data() + box.begin, box.end - box.begin};
    }
};

/// Every leaf its own box, in curve order.
[[nodiscard]] SubdomainCut oneBoxPerLeaf(std::vector<ForestLeaf> const& leaves);

/// Each rank's leaves merged into cuboids: sweeps along x, y and z join two boxes whose union
/// is a box (same extent on the other two axes, touching faces) until no sweep joins any.
/// Deterministic (every rank computes the same boxes from the same leaves). A rank whose
/// blocks form a cuboid (a whole domain, a Hilbert half or octant of a uniform forest) gets
/// one box. O(n log n) per sweep over one rank's leaves.
[[nodiscard]] SubdomainCut mergeRankLeaves(std::vector<ForestLeaf> const& leaves);

} // namespace regolith::domain
