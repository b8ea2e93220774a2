#include "io/checkpoint/RestoreGrains.hpp"

#include "core/Error.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "io/detail/AgreeOnError.hpp"

#include <fmt/format.h>
#include <mpi.h>

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
    std::vector<int> const counts = comm.allGather(static_cast<int>(mine.size()));
    std::vector<int> displs(counts.size(), 0);
    int total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
        displs[r] = total;
        total += counts[r];
    }
    std::vector<double> all(static_cast<std::size_t>(total));
    core::Comm::check(MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE,
                                     all.data(), counts.data(), displs.data(), MPI_DOUBLE,
                                     comm.raw()),
                      "MPI_Allgatherv");
    std::vector<OwnedBox> out;
    for (std::size_t r = 0; r < counts.size(); ++r)
        for (int k = displs[r]; k < displs[r] + counts[r]; k += 6) {
            auto const* v = &all[static_cast<std::size_t>(k)];
            out.push_back({core::AABB{core::Vec3(v[0], v[1], v[2]), core::Vec3(v[3], v[4], v[5])},
                           static_cast<int>(r)});
        }
    return out;
}

void pack(core::SendBuffer& b, GrainState const& g) {
    b << g.uid << g.position << g.velocity << g.angularVelocity << g.orientation << g.force
      << g.torque << g.radius << g.mass << g.type << g.flags
      << static_cast<std::uint64_t>(g.history.size());
    for (particles::HistoryEntry const& e : g.history)
        b << e.partner << e.spring << e.stamp;
}

GrainState unpack(core::RecvBuffer& b) {
    GrainState g;
    std::uint64_t entries = 0;
    b >> g.uid >> g.position >> g.velocity >> g.angularVelocity >> g.orientation >> g.force >>
        g.torque >> g.radius >> g.mass >> g.type >> g.flags >> entries;
    g.history.resize(entries);
    for (particles::HistoryEntry& e : g.history)
        b >> e.partner >> e.spring >> e.stamp;
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
    restoreDynamicState(g, ps, ps.find(g.uid));
}

} // namespace

void restoreGrains(core::Comm const& comm, particles::LocalParticles& local,
                   std::span<GrainState const> grains, std::string const& context) {
    domain::BlockForest const& forest = local.forest();
    std::vector<OwnedBox> const boxes = gatherBlockBoxes(comm, forest);
    core::SparseExchange exchange(comm);
    detail::agreeOnError(comm, [&] {
        for (GrainState const& g : grains) {
            if (!forest.insideDomain(g.position))
                throw core::InputError(
                    fmt::format("{}: grain uid {} at [{}, {}, {}] lies outside the scene's domain "
                                "(the checkpoint was written for another domain)",
                                context, g.uid, g.position.x(), g.position.y(), g.position.z()));
            core::Vec3 const p = forest.wrap(g.position);
            int owner = -1;
            for (OwnedBox const& b : boxes)
                if (b.box.contains(p)) {
                    owner = b.rank;
                    break;
                }
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
