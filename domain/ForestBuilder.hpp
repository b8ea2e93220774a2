#pragma once
/// Global, deterministic set-up of a block forest: root grid, static refinement, 2:1 balance,
/// the order of the leaves along the space-filling curve, their assignment to ranks and the
/// neighbour search. Every rank runs the same set-up and gets the same result; BlockForest
/// then keeps only its own part.
#include "domain/Block.hpp"
#include "domain/ForestGeometry.hpp"
#include "domain/ForestSpec.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::domain {

/// A leaf block of the global forest.
struct ForestLeaf {
    BlockId id;
    LatticeBox box;
    int owner = 0;       ///< set by ForestBuilder::assign
    double weight = 1.0; ///< set by ForestBuilder::assign
};

/// One touching image found by the neighbour search: leaf index and image of the domain.
struct LeafLink {
    std::uint32_t leaf = 0;
    PeriodicImage image{0, 0, 0};
};

/// Throws core::InputError naming domain.refine if the blocks `spec`'s refinement makes at
/// least, with their per-block state shared among `ranks`, exceed this node's memory. Pre:
/// `spec` validated.
void requireRefinementFits(ForestSpec const& spec, int ranks);

/// Builds the whole forest on one rank. Not collective; O(blocks) memory and time for the tree
/// and the curve, O(27 + links) per neighbour query (a search over the root grid cells around
/// the block and their octrees, not over all blocks).
class ForestBuilder {
public:
    /// Validates `spec` (throws core::InputError, see SpecValidation.hpp), creates the root
    /// grid, refines every block whose closed box intersects a refine region (closed) until
    /// it reaches the region's level, then restores 2:1 balance across faces, edges and
    /// corners, periodic images included. Afterwards leaves() is in curve order: root blocks
    /// by the Hilbert index of their root coordinates on the enclosing 2^m grid, and inside a
    /// root depth-first with children in octant (Morton) order. Owners are all 0 until
    /// assign() is called. Throws core::InputError if the refinement would create more than
    /// 2^31 - 1 tree nodes.
    explicit ForestBuilder(ForestSpec const& spec);

    [[nodiscard]] ForestGeometry const& geometry() const { return m_geometry; }
    /// The leaves in curve order.
    [[nodiscard]] std::vector<ForestLeaf> const& leaves() const { return m_leaves; }

    /// Weighs every leaf with `weight(box, level)` (1 if empty) and cuts the curve into
    /// `ranks` contiguous chunks with partitionCurve (SfcPartition.hpp). Throws
    /// core::InputError for a negative or non-finite weight or ranks < 1.
    void assign(BlockWeight const& weight, int ranks);

    /// Every image of every leaf whose closed box touches the closed box of leaf `leaf`,
    /// except `leaf` itself with image 0, sorted by (leaf index, image): curve order.
    /// Replaces the content of `out`.
    void neighbours(std::size_t leaf, std::vector<LeafLink>& out) const;

    /// Index into leaves() of the leaf holding lattice cell `cell`. Pre: cell in the lattice.
    [[nodiscard]] std::size_t leafAt(LatticeCell const& cell) const;

private:
    struct Node {
        BlockId id;
        std::int32_t firstChild = -1; ///< index of child 0 (children are consecutive); -1: leaf
        std::int32_t leaf = -1;       ///< index into m_leaves once ordered
    };

    /// What neighbours() looks for: images touching `self`, skipping `leaf` at image 0.
    struct Search {
        LatticeBox self;
        std::uint32_t leaf;
        PeriodicImage image; ///< of the root being searched
    };

    void refine(RefineRegion const& region);
    /// Appends the leaves under node n (whose image box is `box`) that touch search.self.
    void collectTouching(std::int32_t n, LatticeBox const& box, Search const& search,
                         std::vector<LeafLink>& out) const;
    void refineNode(std::int32_t node, core::AABB const& region, int level);
    void split(std::int32_t node);
    void balance();
    void orderLeaves();
    [[nodiscard]] std::int32_t leafNodeAt(LatticeCell const& cell) const;
    /// Wraps `cell` into the lattice on periodic axes; false if it lies outside on another.
    [[nodiscard]] bool wrapCell(LatticeCell& cell) const;

    ForestGeometry m_geometry;
    std::vector<Node> m_nodes; ///< roots first (node i = root index i), then children by 8
    std::vector<ForestLeaf> m_leaves;
};

} // namespace regolith::domain
