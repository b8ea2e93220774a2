#pragma once
/// What a rank knows about one of its blocks and about each neighbour of it.
#include "core/math/AABB.hpp"
#include "domain/BlockId.hpp"
#include "domain/ForestGeometry.hpp"

#include <cstddef>
#include <functional>
#include <vector>

namespace regolith::domain {

/// How a BlockForest cuts its blocks() from the forest's leaves.
enum class Subdomains {
    Blocks,    ///< one per leaf block (the grid fields' unit)
    RankBoxes, ///< each rank's leaves merged into cuboids (RankBoxes.hpp, mergeRankLeaves)
};

/// Per-block load used to cut the curve into per-rank chunks: (block box, level) -> weight.
/// Must be finite and >= 0, and give the same value on every rank (it is evaluated by every
/// rank for every block during set-up). An empty function means weight 1 for every block.
using BlockWeight = std::function<double(core::AABB const& box, int level)>;

/// One neighbour of a block: one image (periodic copy) of another block, or of the block
/// itself, whose closed box touches the block's closed box (face, edge or corner).
///
/// Shift convention: a point x in the frame of the block holding this link appears at
/// x + shift in the neighbour's frame, so the neighbour's image adjacent to the block is
/// aabb.shifted(-shift). If block A lists B with shift s, B lists A with -s. Across a periodic
/// axis with one or two blocks, the same neighbour (or the block itself) appears in several
/// links with different shifts; those are distinct links.
struct BlockLink {
    BlockId id;
    core::AABB aabb; ///< the neighbour's own box, in its own (unshifted) frame
    int owner = -1;  ///< rank that owns the neighbour
    int level = 0;   ///< the neighbour's refinement level
    core::Vec3 shift = core::Vec3::Zero(); ///< see above; -image * domain extent
    PeriodicImage image{0, 0, 0};          ///< image index: the adjacent copy is image `image`
    LatticeBox lattice;                    ///< the neighbour's own box on the lattice

    /// The neighbour's copy adjacent to the block, in the block's frame.
    [[nodiscard]] core::AABB imageBox() const { return aabb.shifted(-shift); }
};

/// A leaf block of the forest that a block of a BlockForest covers (itself, or one of the
/// leaves a subdomain merges: Subdomains::RankBoxes).
struct CoveredLeaf {
    BlockId id;
    core::AABB aabb;
    LatticeBox lattice;
    std::size_t curveIndex = 0; ///< position along the global curve
    double weight = 1.0;        ///< the BlockWeight it was assigned with
};

/// A block owned by this rank: a leaf of the forest, or with Subdomains::RankBoxes a cuboid
/// of this rank's leaves, named after its first leaf.
struct Block {
    BlockId id;
    core::AABB aabb;
    int level = 0;
    int owner = -1;
    double weight = 1.0;        ///< the BlockWeight it was assigned with (its leaves' sum)
    std::size_t curveIndex = 0; ///< position along the global curve, 0 .. globalBlockCount()-1
                                ///< (of its first leaf)
    LatticeBox lattice;         ///< its box on the forest's lattice
    /// The leaves it covers, in curve order: itself, or the leaves of a merged cuboid.
    std::vector<CoveredLeaf> leaves;
    /// Every touching image except the block itself with zero shift; sorted by the
    /// neighbour's curve position, then by image.
    std::vector<BlockLink> neighbours;
};

} // namespace regolith::domain
