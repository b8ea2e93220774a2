#include "domain/BlockForest.hpp"

#include "domain/ForestBuilder.hpp"
#include "domain/SpecValidation.hpp"

#include <algorithm>

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

BlockForest::BlockForest(core::Comm const& comm, ForestSpec const& spec, BlockWeight const& weight)
    : BlockForest(buildAndAssign(spec, weight, comm.size()), comm.rank(), comm.size()) {}

BlockForest::BlockForest(ForestBuilder const& builder, int rank, int rankCount)
    : m_geometry(builder.geometry())
    , m_rank(rank)
    , m_rankCount(rankCount) {
    auto const& leaves = builder.leaves();
    m_globalBlockCount = leaves.size();

    std::vector<char> busy(static_cast<std::size_t>(rankCount), 0);
    for (ForestLeaf const& leaf : leaves)
        busy[static_cast<std::size_t>(leaf.owner)] = 1;
    m_idleRankCount = static_cast<int>(std::count(busy.begin(), busy.end(), 0));

    // Leaves are in curve order and chunks are contiguous: this rank's part is one range.
    auto const first = std::find_if(leaves.begin(), leaves.end(),
                                    [rank](ForestLeaf const& l) { return l.owner == rank; });
    auto const last =
        std::find_if(first, leaves.end(), [rank](ForestLeaf const& l) { return l.owner != rank; });
    // Real boxes once per leaf rather than once per link.
    std::vector<core::AABB> boxes;
    boxes.reserve(leaves.size());
    for (ForestLeaf const& leaf : leaves)
        boxes.push_back(m_geometry.box(leaf.box));
    m_blocks.reserve(static_cast<std::size_t>(last - first));
    m_index.reserve(static_cast<std::size_t>(last - first));
    std::vector<LeafLink> links;
    for (auto it = first; it != last; ++it) {
        auto const i = static_cast<std::size_t>(it - leaves.begin());
        Block block;
        block.id = it->id;
        block.aabb = boxes[i];
        block.level = it->id.level();
        block.owner = it->owner;
        block.weight = it->weight;
        block.curveIndex = i;
        builder.neighbours(i, links);
        block.neighbours.reserve(links.size());
        for (LeafLink const& l : links) {
            ForestLeaf const& n = leaves[l.leaf];
            block.neighbours.push_back(BlockLink{n.id, boxes[l.leaf], n.owner, n.id.level(),
                                                 m_geometry.shift(l.image), l.image});
            if (n.owner != rank)
                m_neighbourRanks.push_back(n.owner);
        }
        m_localLoad += block.weight;
        m_index.emplace(block.id, m_blocks.size());
        m_blocks.push_back(std::move(block));
    }
    std::sort(m_neighbourRanks.begin(), m_neighbourRanks.end());
    m_neighbourRanks.erase(std::unique(m_neighbourRanks.begin(), m_neighbourRanks.end()),
                           m_neighbourRanks.end());
}

Block const* BlockForest::findBlock(BlockId id) const {
    auto const it = m_index.find(id);
    return it == m_index.end() ? nullptr : &m_blocks[it->second];
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
    if (loc->image == PeriodicImage{0, 0, 0} && m_geometry.latticeBox(from.id).contains(loc->cell))
        return BlockLink{from.id, from.aabb, from.owner, from.level, core::Vec3::Zero(), {0, 0, 0}};
    for (BlockLink const& link : from.neighbours)
        if (link.image == loc->image && m_geometry.latticeBox(link.id).contains(loc->cell))
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
