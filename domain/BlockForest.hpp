#pragma once
/// The block forest as one rank sees it: its own blocks, each with its neighbour links, and
/// the geometric queries particles and fields need (point location, sphere / box overlap with
/// neighbours, periodic wrapping). There is no global block table after construction.
#include "core/mpi/Comm.hpp"
#include "domain/Block.hpp"
#include "domain/ForestGeometry.hpp"
#include "domain/ForestSpec.hpp"

#include <cstddef>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

namespace regolith::domain {

class ForestBuilder;

class BlockForest {
public:
    /// Builds the forest described by `spec` (see ForestBuilder: validation, refinement, 2:1
    /// balance, curve order, assignment of contiguous curve chunks by `weight`) and keeps this
    /// rank's blocks with their neighbour links.
    /// NOT collective: the set-up is global and deterministic, every rank computes the same
    /// assignment from comm.rank() and comm.size() alone, so a rank may construct it alone.
    /// Throws core::InputError (on every rank alike) for an invalid spec or weight.
    /// Cost: O(global blocks) time and transient memory; afterwards O(local blocks + links).
    /// `subdomains` says what blocks() are: the leaves (the grid fields' blocks), or each
    /// rank's leaves merged into cuboids (RankBoxes.hpp; the particles' subdomains). Either
    /// way a block is a box with links to every touching image of the others, and the
    /// queries below answer for those boxes.
    BlockForest(core::Comm const& comm, ForestSpec const& spec, BlockWeight const& weight = {},
                Subdomains subdomains = Subdomains::Blocks);
    /// The same assignment cut twice from one global set-up: as blocks (the grid fields') and
    /// as `particles` (the particles' subdomains). Not collective, as the constructor.
    [[nodiscard]] static std::pair<BlockForest, BlockForest> blocksAnd(core::Comm const& comm,
                                                                       ForestSpec const& spec,
                                                                       BlockWeight const& weight,
                                                                       Subdomains particles);

    // ---- the forest as a whole (identical on every rank) ----------------------------------
    [[nodiscard]] ForestGeometry const& geometry() const { return m_geometry; }
    [[nodiscard]] core::AABB const& domain() const { return m_geometry.domain(); }
    [[nodiscard]] std::array<bool, 3> const& periodic() const { return m_geometry.periodic(); }
    [[nodiscard]] std::array<int, 3> const& rootBlocks() const { return m_geometry.rootBlocks(); }
    /// Deepest refinement level of any block (0 without refinement).
    [[nodiscard]] int maxLevel() const { return m_geometry.maxLevel(); }
    /// Leaves of the forest (whatever the subdomains).
    [[nodiscard]] std::size_t globalBlockCount() const { return m_globalBlockCount; }
    /// Subdomains of all ranks: globalBlockCount() for Subdomains::Blocks, fewer if merged.
    [[nodiscard]] std::size_t globalSubdomainCount() const { return m_globalSubdomainCount; }
    /// Per axis: whether every subdomain of every rank spans the domain along it.
    [[nodiscard]] std::array<bool, 3> const& spannedBySubdomains() const { return m_spanned; }
    [[nodiscard]] Subdomains subdomains() const { return m_subdomains; }
    [[nodiscard]] int rank() const { return m_rank; }
    [[nodiscard]] int rankCount() const { return m_rankCount; }
    /// Ranks that own no block (more ranks than blocks, or a few very heavy blocks). The app
    /// may warn about them; the library does not print.
    [[nodiscard]] int idleRankCount() const { return m_idleRankCount; }

    // ---- this rank ------------------------------------------------------------------------
    /// This rank's blocks, in curve order.
    [[nodiscard]] std::span<Block const> blocks() const { return m_blocks; }
    [[nodiscard]] bool isIdle() const { return m_blocks.empty(); }
    /// Sum of the weights of this rank's blocks.
    [[nodiscard]] double localLoad() const { return m_localLoad; }
    /// The local block with this id, or covering the leaf with this id; nullptr if this rank
    /// does not own it.
    [[nodiscard]] Block const* findBlock(BlockId id) const;
    /// The index into block.leaves of the leaf whose half-open box holds p. Pre: p in the
    /// domain (wrapped) and in block's box.
    [[nodiscard]] std::size_t leafContaining(Block const& block, core::Vec3 const& p) const;
    /// Ranks other than this one that own a neighbour of a local block, ascending. Symmetric:
    /// q is in rank r's list iff r is in q's.
    [[nodiscard]] std::vector<int> const& neighbourRanks() const { return m_neighbourRanks; }

    // ---- queries (local, no communication) ------------------------------------------------
    /// The local block whose half-open box holds p, or nullptr (p owned by another rank, or
    /// outside [min, max) on some axis: p is not wrapped, use wrap() first on periodic axes).
    /// A point on a face shared by two blocks belongs to the upper one. O(maxLevel) lookups.
    [[nodiscard]] Block const* localBlockContaining(core::Vec3 const& p) const;
    /// The block image holding p, where p is given in the frame of local block `from` and may
    /// lie in `from` itself (returned as a link to `from` with zero shift) or in any of its
    /// neighbour images, also beyond the domain on a periodic axis. nullopt if p lies outside
    /// the domain on a non-periodic axis or beyond the neighbour images. The returned link's
    /// shift maps p into the owner's frame: p + shift lies in link.aabb (up to rounding, which
    /// never changes the answer: the decision is made on the lattice of wrap(p)).
    /// Pre: `from` is one of blocks().
    [[nodiscard]] std::optional<BlockLink> blockContaining(Block const& from,
                                                           core::Vec3 const& p) const;
    /// The links of `from` whose image (link.imageBox()) the ball (center, radius) reaches
    /// into: closest-point distance < radius (AABB::intersectsSphere, exact for a box). center
    /// in the frame of `from`. Only `from`'s links are searched: a ball reaching further than
    /// the neighbour images is reported for the part that overlaps them. Appends to `out`.
    void linksOverlappingSphere(Block const& from, core::Vec3 const& center, double radius,
                                std::vector<BlockLink const*>& out) const;
    [[nodiscard]] std::vector<BlockLink const*>
    linksOverlappingSphere(Block const& from, core::Vec3 const& center, double radius) const;
    /// The links of `from` whose image's closed box intersects the closed `box` (given in the
    /// frame of `from`): touching counts, so from.aabb yields every link (up to rounding of
    /// image faces on a periodic boundary, where aabb.shifted(-shift) may miss the touching
    /// face by an ulp). Appends to `out`.
    void linksOverlappingBox(Block const& from, core::AABB const& box,
                             std::vector<BlockLink const*>& out) const;
    [[nodiscard]] std::vector<BlockLink const*> linksOverlappingBox(Block const& from,
                                                                    core::AABB const& box) const;
    /// See ForestGeometry::wrap / insideDomain.
    [[nodiscard]] core::Vec3 wrap(core::Vec3 const& p) const { return m_geometry.wrap(p); }
    [[nodiscard]] bool insideDomain(core::Vec3 const& p) const {
        return m_geometry.insideDomain(p);
    }

private:
    /// Keeps the part of an assigned global forest that `rank` owns.
    BlockForest(ForestBuilder const& builder, int rank, int rankCount, Subdomains subdomains);

    ForestGeometry m_geometry;
    int m_rank = 0;
    int m_rankCount = 1;
    std::size_t m_globalBlockCount = 0;
    std::size_t m_globalSubdomainCount = 0;
    std::array<bool, 3> m_spanned{false, false, false};
    Subdomains m_subdomains = Subdomains::Blocks;
    int m_idleRankCount = 0;
    double m_localLoad = 0.0;
    std::vector<Block> m_blocks;
    /// Every covered leaf's id -> (local block, index into its leaves).
    std::unordered_map<BlockId, std::pair<std::size_t, std::size_t>> m_index;
    std::vector<int> m_neighbourRanks;
};

} // namespace regolith::domain
