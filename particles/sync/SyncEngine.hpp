#pragma once
/// Internals of ParticleSync shared by its source files: the per-rank view of the forest the
/// algorithms need and the exchange that carries one round of records.
#include "core/mpi/Buffer.hpp"
#include "core/mpi/Comm.hpp"
#include "core/mpi/CommCounters.hpp"
#include "core/mpi/NeighbourExchange.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <unordered_map>
#include <vector>

namespace regolith::particles {

class ParticleSync::Impl {
public:
    Impl(core::Comm const& comm, domain::BlockForest const& forest, SyncConfig config);

    /// The buffer for `rank` in the current round.
    core::SendBuffer& out(int rank);
    /// Sends the round's buffers and hands every received buffer to `f(from, buffer)` in
    /// ascending source rank; adds the traffic to `stats`. With the sparse exchange (SOS,
    /// hybrid), `raiseFlag` is this rank's say in flagRaised() afterwards. COLLECTIVE.
    template <class F>
    void exchange(core::CommStats& stats, F&& f, bool raiseFlag = false) {
        if (m_neighbour) {
            m_neighbour->start();
            m_neighbour->wait(f);
        } else {
            m_sparse->start();
            if (raiseFlag)
                m_sparse->raiseFlag();
            m_sparse->wait(f);
        }
        // The exchange's own count of this call: NNS sends its size messages to every
        // neighbour rank, SOS (NBX) only to ranks with records.
        stats += m_neighbour ? m_neighbour->counters().last() : m_sparse->counters().last();
    }

    /// Whether some rank raised its flag in the last sparse exchange (false with NNS's).
    [[nodiscard]] bool flagRaised() const { return m_sparse && m_sparse->flagRaised(); }

    /// Smallest edge of block `id` and of all its neighbours (NNS limit), by raw id.
    [[nodiscard]] double edgeAround(std::uint64_t id) const { return m_edgeAround.at(id); }
    /// Distinct (rank, raw id) of the neighbour blocks of local block `id`.
    [[nodiscard]] std::vector<BlockRef> const& neighbourBlocks(std::uint64_t id) const {
        return m_neighbourBlocks.at(id);
    }
    /// Indices into block(id).neighbours of the links in each direction (dx, dy, dz) in
    /// {-1, 0, 1}^3 from the block, at (dx + 1) + 3 (dy + 1) + 9 (dz + 1). A link is filed
    /// under 0 on an axis unless its image box lies wholly beyond a face there, so the
    /// grouping errs on the inclusive side.
    using LinkGroups = std::array<std::vector<std::uint32_t>, 27>;
    [[nodiscard]] LinkGroups const& linksByDirection(std::uint64_t id) const {
        return m_linksByDirection.at(id);
    }
    /// Calls f(link) for every link of `block` whose direction the ball (x, r) may reach:
    /// only the faces the ball crosses (with deepInside's slack) can lead to a neighbour it
    /// overlaps, so a grain near one face visits a few links, not all 26 or more. `groups` is
    /// linksByDirection(block), looked up once by callers that visit many grains.
    template <class F>
    void forEachReachableLink(domain::Block const& block, LinkGroups const& groups,
                              core::Vec3 const& x, double r, F&& f) const {
        double const reach = r * (1.0 + ParticleSync::kOverlapMargin) + m_imageSlack;
        core::Vec3 const& lo = block.aabb.min;
        core::Vec3 const& hi = block.aabb.max;
        // Group index (dx + 1) + 3 (dy + 1) + 9 (dz + 1): the range of d per axis, scaled.
        int const x0 = x[0] - reach < lo[0] ? 0 : 1, x1 = x[0] + reach > hi[0] ? 2 : 1;
        int const y0 = x[1] - reach < lo[1] ? 0 : 3, y1 = x[1] + reach > hi[1] ? 6 : 3;
        int const z0 = x[2] - reach < lo[2] ? 0 : 9, z1 = x[2] + reach > hi[2] ? 18 : 9;
        for (int z = z0; z <= z1; z += 9)
            for (int y = y0; y <= y1; y += 3)
                for (int g = z + y + x0; g <= z + y + x1; ++g)
                    for (std::uint32_t l : groups[static_cast<std::size_t>(g)])
                        f(block.neighbours[l]);
    }
    [[nodiscard]] core::Vec3 const& period() const { return m_period; }
    /// The periodic axes the particles hold no images on (wrappedAxes): no link across them.
    [[nodiscard]] std::array<bool, 3> const& wrapped() const { return m_wrapped; }
    /// What deepInside measures against in one block: the box from which the reach is
    /// measured (the block's box with every face on an open, non-periodic, domain boundary
    /// moved to infinity: no block lies beyond it), and the block's box itself, which the
    /// centre must then lie strictly inside (the master stays in its block).
    struct DeepTest {
        core::AABB reachBox;
        core::AABB box;
        bool open = false; ///< some face lies on an open domain boundary
    };
    /// Whether the ball (x, r) of a master of a block lies so deep inside it that no other
    /// block can need a copy of it: its distance to every face with blocks beyond it exceeds
    /// the copy criterion's reach plus an absolute slack that covers the rounding of periodic
    /// images (x + k * period). `t` is the block's deepTest. The common case of a small grain;
    /// lets the sync skip the link loop (copyNeeded would be false for every link). A block
    /// with no open face pays what the plain reach test costs.
    [[nodiscard]] bool deepInside(DeepTest const& t, core::Vec3 const& x, double r) const {
        double const reach = r * (1.0 + ParticleSync::kOverlapMargin) + m_imageSlack;
        // Non-short-circuit `&`: no branch per face, so that the scan over every master of a
        // block (CopyScan) runs without mispredictions where deep and shallow grains alternate.
        bool deep = true;
        for (int a = 0; a < 3; ++a)
            deep = deep & (std::min(x[a] - t.reachBox.min[a], t.reachBox.max[a] - x[a]) > reach);
        if (!t.open)
            return deep;
        bool inside = true;
        for (int a = 0; a < 3; ++a)
            inside = inside & (x[a] > t.box.min[a]) & (x[a] < t.box.max[a]);
        return deep & inside;
    }
    [[nodiscard]] DeepTest const& deepTest(std::uint64_t id) const { return m_deepTest.at(id); }
    /// A cheap pre-test for copyNeeded through a link: false only if the ball at local
    /// position `x` (the holder's frame) certainly misses the link's image box (box against
    /// box, with the same slack as deepInside).
    [[nodiscard]] bool mayReach(domain::BlockLink const& link, core::Vec3 const& x,
                                double r) const {
        double const reach = r * (1.0 + ParticleSync::kOverlapMargin) + m_imageSlack;
        core::AABB const box = link.imageBox();
        return (x.array() + reach > box.min.array()).all() &&
               (x.array() - reach < box.max.array()).all();
    }
    [[nodiscard]] domain::BlockForest const& forest() const { return *m_forest; }
    /// Two work lists for the per-master code (0: targets, 1: new holders), kept between
    /// calls so that a grain near a face costs no allocation.
    [[nodiscard]] std::vector<CopyRef>& scratch(std::size_t k) { return m_scratch[k]; }
    /// A work list of copy indices for spread, kept between calls.
    [[nodiscard]] std::vector<std::size_t>& scratchIndices() { return m_scratchIndices; }
    /// The masters round 1 visits in one block (scanMasters), kept between calls.
    [[nodiscard]] std::vector<std::uint32_t>& scratchMasters() { return m_scratchMasters; }
    [[nodiscard]] core::Comm const& comm() const { return m_comm; }
    [[nodiscard]] int rank() const { return m_comm.rank(); }

private:
    core::Comm m_comm;
    domain::BlockForest const* m_forest;
    core::Vec3 m_period;
    std::array<bool, 3> m_wrapped{false, false, false};
    double m_imageSlack = 0.0;                            ///< see deepInside
    std::unique_ptr<core::NeighbourExchange> m_neighbour; ///< NNS: neighbour ranks only
    std::unique_ptr<core::SparseExchange> m_sparse;       ///< SOS / hybrid: any rank
    std::unordered_map<std::uint64_t, double> m_edgeAround;
    std::unordered_map<std::uint64_t, DeepTest> m_deepTest;
    std::unordered_map<std::uint64_t, LinkGroups> m_linksByDirection;
    std::unordered_map<std::uint64_t, std::vector<BlockRef>> m_neighbourBlocks;
    std::array<std::vector<CopyRef>, 2> m_scratch;
    std::vector<std::size_t> m_scratchIndices;
    std::vector<std::uint32_t> m_scratchMasters;
};

} // namespace regolith::particles
