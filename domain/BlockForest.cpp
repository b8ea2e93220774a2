#include "domain/BlockForest.hpp"

#include "core/Error.hpp"
#include "domain/ForestBuilder.hpp"
#include "domain/RankBoxes.hpp"
#include "domain/SpecValidation.hpp"

#include <algorithm>
#include <utility>

namespace regolith::domain {

namespace {

/// Builds the global forest once; kept out of BlockForest so that it is gone after set-up.
ForestBuilder buildAndAssign(ForestSpec const& spec, BlockWeight const& weight, int ranks) {
    validate(spec);
    requireRefinementFits(spec, ranks);
    ForestBuilder builder(spec);
    builder.assign(weight, ranks);
    return builder;
}

} // namespace

BlockForest::BlockForest(core::Comm const& comm, ForestSpec const& spec, BlockWeight const& weight,
                         Subdomains subdomains)
    : BlockForest(buildAndAssign(spec, weight, comm.size()), comm.rank(), comm.size(), subdomains) {
}

std::pair<BlockForest, BlockForest> BlockForest::blocksAnd(core::Comm const& comm,
                                                           ForestSpec const& spec,
                                                           BlockWeight const& weight,
                                                           Subdomains particles) {
    ForestBuilder const builder = buildAndAssign(spec, weight, comm.size());
    return {BlockForest(builder, comm.rank(), comm.size(), Subdomains::Blocks),
            BlockForest(builder, comm.rank(), comm.size(), particles)};
}

BlockForest::BlockForest(ForestBuilder const& builder, int rank, int rankCount,
                         Subdomains subdomains)
    : m_geometry(builder.geometry())
    , m_rank(rank)
    , m_rankCount(rankCount)
    , m_subdomains(subdomains) {
    auto const& leaves = builder.leaves();
    m_globalBlockCount = leaves.size();

    std::vector<char> busy(static_cast<std::size_t>(rankCount), 0);
    for (ForestLeaf const& leaf : leaves)
        busy[static_cast<std::size_t>(leaf.owner)] = 1;
    m_idleRankCount = static_cast<int>(std::count(busy.begin(), busy.end(), 0));

    SubdomainCut const cut =
        subdomains == Subdomains::RankBoxes ? mergeRankLeaves(leaves) : oneBoxPerLeaf(leaves);
    m_globalSubdomainCount = cut.boxes.size();
    for (int a = 0; a < 3; ++a) {
        auto const u = static_cast<std::size_t>(a);
        m_spanned[u] = !cut.boxes.empty();
        for (RankBox const& box : cut.boxes)
            m_spanned[u] = m_spanned[u] && box.lattice.lo[u] == 0 &&
                           box.lattice.hi[u] == m_geometry.latticeSize(a);
    }
    std::vector<std::uint32_t> boxOf(leaves.size()); // per leaf, its box
    for (std::size_t b = 0; b < cut.boxes.size(); ++b)
        for (std::uint32_t l : cut.leavesOf(cut.boxes[b]))
            boxOf[l] = static_cast<std::uint32_t>(b);
    std::vector<LeafLink> leafLinks;
    std::vector<LeafLink> links; // (box, image) of the block's links
    for (std::size_t b = 0; b < cut.boxes.size(); ++b) {
        RankBox const& box = cut.boxes[b];
        if (box.owner != rank)
            continue;
        auto const mine = cut.leavesOf(box);
        ForestLeaf const& first = leaves[mine.front()];
        Block block;
        block.id = first.id;
        block.aabb = m_geometry.box(box.lattice);
        block.level = first.id.level();
        block.owner = rank;
        block.weight = 0.0;
        block.curveIndex = mine.front();
        block.lattice = box.lattice;
        // A box touches another's image iff one of its leaves touches one of the other's.
        links.clear();
        for (std::uint32_t l : mine) {
            ForestLeaf const& leaf = leaves[l];
            block.leaves.push_back(
                CoveredLeaf{leaf.id, m_geometry.box(leaf.box), leaf.box, l, leaf.weight});
            block.weight += leaf.weight;
            m_index.emplace(leaf.id, std::pair{m_blocks.size(), block.leaves.size() - 1});
            builder.neighbours(l, leafLinks);
            for (LeafLink const& n : leafLinks)
                if (boxOf[n.leaf] != b || n.image != PeriodicImage{0, 0, 0})
                    links.push_back(LeafLink{boxOf[n.leaf], n.image});
        }
        // Boxes are sorted by their first leaf: box order is curve order.
        std::sort(links.begin(), links.end(), [](LeafLink const& x, LeafLink const& y) {
            return x.leaf != y.leaf ? x.leaf < y.leaf : x.image < y.image;
        });
        links.erase(std::unique(links.begin(), links.end(),
                                [](LeafLink const& x, LeafLink const& y) {
                                    return x.leaf == y.leaf && x.image == y.image;
                                }),
                    links.end());
        block.neighbours.reserve(links.size());
        for (LeafLink const& l : links) {
            RankBox const& n = cut.boxes[l.leaf];
            BlockId const id = leaves[cut.leavesOf(n).front()].id;
            block.neighbours.push_back(BlockLink{id, m_geometry.box(n.lattice), n.owner, id.level(),
                                                 m_geometry.shift(l.image), l.image, n.lattice});
            if (n.owner != rank)
                m_neighbourRanks.push_back(n.owner);
        }
        m_localLoad += block.weight;
        m_blocks.push_back(std::move(block));
    }
    std::sort(m_neighbourRanks.begin(), m_neighbourRanks.end());
    m_neighbourRanks.erase(std::unique(m_neighbourRanks.begin(), m_neighbourRanks.end()),
                           m_neighbourRanks.end());
}

Block const* BlockForest::findBlock(BlockId id) const {
    auto const it = m_index.find(id);
    return it == m_index.end() ? nullptr : &m_blocks[it->second.first];
}

std::size_t BlockForest::leafContaining(Block const& block, core::Vec3 const& p) const {
    if (block.leaves.size() == 1)
        return 0;
    auto const loc = m_geometry.locate(p);
    if (loc)
        for (int level = 0; level <= m_geometry.maxLevel(); ++level) {
            auto const it = m_index.find(m_geometry.blockAt(loc->cell, level));
            if (it != m_index.end() && &m_blocks[it->second.first] == &block)
                return it->second.second;
        }
    throw core::Error("BlockForest::leafContaining: the point lies outside the block");
}

Block const* BlockForest::localBlockContaining(core::Vec3 const& p) const {
    if (m_blocks.empty())
        return nullptr;
    core::AABB const& d = m_geometry.domain();
    if (!((p.array() >= d.min.array()).all() && (p.array() < d.max.array()).all()))
        return nullptr;
    auto const loc = m_geometry.locate(p);
    if (!loc)
        return nullptr;
    for (int level = 0; level <= m_geometry.maxLevel(); ++level)
        if (Block const* b = findBlock(m_geometry.blockAt(loc->cell, level)))
            return b;
    return nullptr;
}

std::optional<BlockLink> BlockForest::blockContaining(Block const& from,
                                                      core::Vec3 const& p) const {
    auto const loc = m_geometry.locate(p);
    if (!loc)
        return std::nullopt;
    if (loc->image == PeriodicImage{0, 0, 0} && from.lattice.contains(loc->cell))
        return BlockLink{from.id,   from.aabb,   from.owner, from.level, core::Vec3::Zero(),
                         {0, 0, 0}, from.lattice};
    for (BlockLink const& link : from.neighbours)
        if (link.image == loc->image && link.lattice.contains(loc->cell))
            return link;
    return std::nullopt;
}

void BlockForest::linksOverlappingSphere(Block const& from, core::Vec3 const& center, double radius,
                                         std::vector<BlockLink const*>& out) const {
    for (BlockLink const& link : from.neighbours)
        if (link.imageBox().intersectsSphere(center, radius))
            out.push_back(&link);
}

std::vector<BlockLink const*> BlockForest::linksOverlappingSphere(Block const& from,
                                                                  core::Vec3 const& center,
                                                                  double radius) const {
    std::vector<BlockLink const*> out;
    linksOverlappingSphere(from, center, radius, out);
    return out;
}

void BlockForest::linksOverlappingBox(Block const& from, core::AABB const& box,
                                      std::vector<BlockLink const*>& out) const {
    for (BlockLink const& link : from.neighbours)
        if (link.imageBox().intersectsClosed(box))
            out.push_back(&link);
}

std::vector<BlockLink const*> BlockForest::linksOverlappingBox(Block const& from,
                                                               core::AABB const& box) const {
    std::vector<BlockLink const*> out;
    linksOverlappingBox(from, box, out);
    return out;
}

} // namespace regolith::domain
