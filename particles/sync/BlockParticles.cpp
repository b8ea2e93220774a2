#include "particles/sync/BlockParticles.hpp"

#include "core/Error.hpp"
#include "particles/detection/PeriodicFrame.hpp"

#include <algorithm>
#include <string>
#include <utility>

namespace regolith::particles {

LocalParticles::LocalParticles(domain::BlockForest const& forest)
    : m_forest(&forest) {
    m_blocks.reserve(forest.blocks().size());
    for (domain::Block const& b : forest.blocks()) {
        m_byId.emplace_back(b.id.raw(), m_blocks.size());
        m_blocks.push_back(BlockParticles{&b, ParticleStorage{}, {}, {}});
        m_blocks.back().particles.setWrapPeriod(wrapPeriod());
    }
    std::sort(m_byId.begin(), m_byId.end());
}

core::Vec3 LocalParticles::wrapPeriod() const {
    return PeriodicFrame(*m_forest).wrapPeriod();
}

BlockParticles* LocalParticles::find(std::uint64_t blockId) {
    return const_cast<BlockParticles*>(std::as_const(*this).find(blockId));
}

BlockParticles const* LocalParticles::find(std::uint64_t blockId) const {
    // The sync looks a block up per copy: a scan while there are a few blocks (the usual
    // layouts), by binary search beyond (a refined forest gives a rank thousands of blocks,
    // and the scan made the set-up of 42,000 blocks take minutes).
    if (m_blocks.size() <= 8) {
        for (BlockParticles const& b : m_blocks)
            if (b.block->id.raw() == blockId)
                return &b;
        return nullptr;
    }
    auto const at = std::lower_bound(m_byId.begin(), m_byId.end(),
                                     std::pair<std::uint64_t, std::size_t>{blockId, 0});
    return at != m_byId.end() && at->first == blockId ? &m_blocks[at->second] : nullptr;
}

bool LocalParticles::addMaster(ParticleInit p) {
    if (!m_forest->insideDomain(p.position))
        return false;
    p.position = m_forest->wrap(p.position);
    domain::Block const* block = m_forest->localBlockContaining(p.position);
    if (block == nullptr)
        return false;
    BlockParticles* bp = find(block->id.raw());
    p.flags.set(Flag::Shadow, false);
    p.image = kNoImage;
    p.owner = BlockRef{m_forest->rank(), block->id.raw()};
    if (bp->particles.contains(p.uid))
        throw core::Error("particle uid " + std::to_string(p.uid) +
                          " inserted twice in the same block");
    bp->particles.add(p);
    return true;
}

void LocalParticles::adoptMasters(ParticleStorage&& masters) {
    if (m_blocks.size() == 1 && m_blocks[0].particles.empty()) {
        domain::Block const& block = *m_blocks[0].block;
        BlockRef const owner{m_forest->rank(), block.id.raw()};
        bool asIs = true;
        for (std::size_t i = 0; i < masters.size() && asIs; ++i) {
            core::Vec3 const& x = masters.position(i);
            asIs = masters.flags(i).isMaster() && isZero(masters.image(i)) &&
                   masters.owner(i) == owner && m_forest->insideDomain(x) &&
                   m_forest->wrap(x) == x && block.aabb.contains(x);
        }
        if (asIs) {
            m_blocks[0].particles = std::move(masters);
            m_blocks[0].particles.setWrapPeriod(wrapPeriod());
            return;
        }
    }
    for (std::size_t i = 0; i < masters.size(); ++i) {
        ParticleInit p;
        static_cast<GrainRow&>(p) = masters.row(i);
        p.owner = masters.owner(i);
        p.fields = masters.fieldValues(i);
        if (!addMaster(p))
            throw core::Error("particle uid " + std::to_string(p.uid) +
                              " lies in no block of this rank");
    }
    masters.clear();
}

std::vector<LocalParticles::LeafLoad>
LocalParticles::loadPerLeaf(std::size_t b, std::span<std::uint32_t const> contacts) const {
    BlockParticles const& bp = m_blocks[b];
    std::vector<LeafLoad> load(bp.block->leaves.size());
    bool const one = load.size() == 1;
    bp.particles.forEachMaster([&](std::size_t i) {
        LeafLoad& l = load[one ? 0 : m_forest->leafContaining(*bp.block, bp.particles.position(i))];
        ++l.grains;
        if (!contacts.empty())
            l.contacts += contacts[i];
    });
    return load;
}

void LocalParticles::requireCountsCover(ContactCounts const& counts) const {
    bool covers = counts.size() == m_blocks.size();
    for (std::size_t b = 0; covers && b < m_blocks.size(); ++b)
        covers = counts[b].size() == m_blocks[b].particles.size();
    if (!covers)
        throw core::Error("contact counts: " + std::to_string(counts.size()) +
                          " blocks' counts for " + std::to_string(m_blocks.size()) +
                          " local blocks, or a block's count of copies differs: the counts were "
                          "taken before the storages changed");
}

ContactCounts LocalParticles::contactsStamped(std::uint32_t stamp) const {
    ContactCounts counts(m_blocks.size());
    for (std::size_t b = 0; b < m_blocks.size(); ++b) {
        ParticleStorage const& ps = m_blocks[b].particles;
        counts[b].assign(ps.size(), 0);
        ps.forEachMaster([&](std::size_t i) {
            ContactHistory const& h = ps.history(i);
            counts[b][i] = static_cast<std::uint32_t>(std::count_if(
                h.begin(), h.end(), [stamp](HistoryEntry const& e) { return e.stamp == stamp; }));
        });
    }
    return counts;
}

std::size_t LocalParticles::countMasters() const {
    std::size_t n = 0;
    for (BlockParticles const& b : m_blocks)
        n += b.particles.countMasters();
    return n;
}

std::size_t LocalParticles::countCopies() const {
    std::size_t n = 0;
    for (BlockParticles const& b : m_blocks)
        n += b.particles.size();
    return n;
}

} // namespace regolith::particles
