#include "io/checkpoint/RestoreGrains.hpp"

#include "core/Error.hpp"
#include "core/mpi/AgreeOnInputError.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "particles/sync/SyncMessages.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace regolith::io {

namespace {

struct OwnedBox {
    core::AABB box;
    int rank = -1;
};

/// Every rank's block boxes, on every rank (the forest keeps only its own blocks).
std::vector<OwnedBox> gatherBlockBoxes(core::Comm const& comm, domain::BlockForest const& forest) {
    std::vector<double> mine;
    for (domain::Block const& b : forest.blocks())
        for (core::Vec3 const* v : {&b.aabb.min, &b.aabb.max})
            mine.insert(mine.end(), v->data(), v->data() + 3);
    std::vector<int> counts;
    std::vector<double> const all = comm.allGatherVarying<double>(mine, &counts);
    std::vector<OwnedBox> out;
    int begin = 0; // rank r's boxes: [begin, begin + counts[r]) of `all`, 6 values each
    for (std::size_t r = 0; r < counts.size(); begin += counts[r], ++r)
        for (int k = begin; k < begin + counts[r]; k += 6) {
            auto const* v = &all[static_cast<std::size_t>(k)];
            out.push_back({core::AABB{core::Vec3(v[0], v[1], v[2]), core::Vec3(v[3], v[4], v[5])},
                           static_cast<int>(r)});
        }
    return out;
}

/// Which rank owns the block containing a point: the gathered boxes bucketed by the root
/// block their centre lies in (a refined root holds its children), so a look-up tests the
/// few boxes of one root block instead of all of them.
class OwnerLookup {
public:
    OwnerLookup(std::vector<OwnedBox> boxes, domain::BlockForest const& forest)
        : m_boxes(std::move(boxes))
        , m_domain(forest.domain())
        , m_roots(forest.rootBlocks()) {
        m_buckets.resize(static_cast<std::size_t>(m_roots[0]) * m_roots[1] * m_roots[2]);
        for (std::size_t k = 0; k < m_boxes.size(); ++k)
            m_buckets[bucket(m_boxes[k].box.center())].push_back(k);
    }
    /// The owner rank, or -1 if no box contains p.
    [[nodiscard]] int owner(core::Vec3 const& p) const {
        for (std::size_t k : m_buckets[bucket(p)])
            if (m_boxes[k].box.contains(p))
                return m_boxes[k].rank;
        // A point on a root face may round into the neighbouring bucket: search them all.
        for (OwnedBox const& b : m_boxes)
            if (b.box.contains(p))
                return b.rank;
        return -1;
    }

private:
    [[nodiscard]] std::size_t bucket(core::Vec3 const& p) const {
        std::size_t index = 0;
        for (int a = 2; a >= 0; --a) {
            double const edge =
                (m_domain.max[a] - m_domain.min[a]) / m_roots[static_cast<std::size_t>(a)];
            auto i = static_cast<long long>(std::floor((p[a] - m_domain.min[a]) / edge));
            i = std::clamp<long long>(i, 0, m_roots[static_cast<std::size_t>(a)] - 1);
            index = index * static_cast<std::size_t>(m_roots[static_cast<std::size_t>(a)]) +
                    static_cast<std::size_t>(i);
        }
        return index;
    }

    std::vector<OwnedBox> m_boxes;
    core::AABB m_domain;
    std::array<int, 3> m_roots;
    std::vector<std::vector<std::size_t>> m_buckets;
};

void pack(core::SendBuffer& b, GrainState const& g) {
    particles::sync_detail::writeRow<particles::sync_detail::RowPart::Every>(b, g);
    b << static_cast<std::uint64_t>(g.history.size());
    for (particles::HistoryEntry const& e : g.history)
        b << e.partner << e.spring << e.stamp;
    b << g.fields;
}

GrainState unpack(core::RecvBuffer& b) {
    GrainState g;
    std::uint64_t entries = 0;
    particles::sync_detail::readRow<particles::sync_detail::RowPart::Every>(b, g);
    b >> entries;
    g.history.resize(entries);
    for (particles::HistoryEntry& e : g.history)
        b >> e.partner >> e.spring >> e.stamp;
    b >> g.fields;
    return g;
}

void addRestored(particles::LocalParticles& local, GrainState const& g) {
    if (!local.addMaster(toParticleInit(g)))
        throw core::Error(fmt::format("restart: grain uid {} was sent to rank {}, which owns no "
                                      "block containing it",
                                      g.uid, local.forest().rank()));
    domain::BlockForest const& forest = local.forest();
    domain::Block const* block = forest.localBlockContaining(forest.wrap(g.position));
    particles::ParticleStorage& ps = local.find(block->id.raw())->particles;
    restoreHistory(g, ps, ps.find(g.uid));
}

} // namespace

void restoreGrains(core::Comm const& comm, particles::LocalParticles& local,
                   std::span<GrainState const> grains, std::string const& context) {
    domain::BlockForest const& forest = local.forest();
    OwnerLookup const owners(gatherBlockBoxes(comm, forest), forest);
    core::SparseExchange exchange(comm);
    core::agreeOnInputError(comm, [&] {
        for (GrainState const& g : grains) {
            if (!forest.insideDomain(g.position))
                throw core::InputError(
                    fmt::format("{}: grain uid {} at [{}, {}, {}] lies outside the scene's domain "
                                "(the checkpoint was written for another domain)",
                                context, g.uid, g.position.x(), g.position.y(), g.position.z()));
            core::Vec3 const p = forest.wrap(g.position);
            int const owner = owners.owner(p);
            if (owner < 0)
                throw core::InputError(
                    fmt::format("{}: grain uid {} lies in no block", context, g.uid));
            pack(exchange.sendBuffer(owner), g);
        }
    });
    exchange.start();
    exchange.wait([&](int /*from*/, core::RecvBuffer& in) {
        while (!in.exhausted())
            addRestored(local, unpack(in));
    });
}

} // namespace regolith::io
