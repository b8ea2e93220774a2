#include "particles/sync/UniqueUids.hpp"

#include "core/Error.hpp"
#include "core/mpi/SparseExchange.hpp"
#include "domain/BlockId.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

namespace regolith::particles {

namespace {

/// One master as its checking rank sees it.
struct MasterEntry {
    Uid uid = kInvalidUid;
    int rank = -1;
    std::uint64_t block = 0;
    core::Vec3 position = core::Vec3::Zero();

    [[nodiscard]] auto key() const {
        return std::tuple(uid, rank, block, position[0], position[1], position[2]);
    }
};

std::string describe(MasterEntry const& e) {
    return fmt::format("({:.17g}, {:.17g}, {:.17g}) in block {} on rank {}", e.position[0],
                       e.position[1], e.position[2], domain::BlockId::fromRaw(e.block).toString(),
                       e.rank);
}

} // namespace

void verifyUniqueMasters(LocalParticles const& local, core::Comm const& comm) {
    auto const ranks = static_cast<std::uint64_t>(comm.size());
    core::SparseExchange exchange(comm);
    for (BlockParticles const& bp : local.blocks()) {
        ParticleStorage const& ps = bp.particles;
        ps.forEachMaster([&](std::size_t i) {
            auto const dest = static_cast<int>(ps.uid(i) % ranks);
            exchange.sendBuffer(dest) << ps.uid(i) << bp.block->id.raw() << ps.position(i);
        });
    }
    exchange.start();
    std::vector<MasterEntry> entries;
    exchange.wait([&entries](int from, core::RecvBuffer& in) {
        while (!in.exhausted()) {
            MasterEntry& e = entries.emplace_back();
            e.rank = from;
            in >> e.uid >> e.block >> e.position;
        }
    });
    std::sort(entries.begin(), entries.end(),
              [](MasterEntry const& a, MasterEntry const& b) { return a.key() < b.key(); });

    // Distinct duplicated uids here, and the first two entries of the smallest one.
    std::uint64_t duplicated = 0;
    std::size_t first = entries.size();
    for (std::size_t i = 1; i < entries.size(); ++i) {
        if (entries[i].uid != entries[i - 1].uid)
            continue;
        if (i == 1 || entries[i - 2].uid != entries[i].uid) {
            ++duplicated;
            if (first == entries.size())
                first = i - 1;
        }
    }
    std::uint64_t const total = comm.allReduce(duplicated, core::ReduceOp::Sum);
    if (total == 0)
        return;
    // As unsigned long long: Open MPI 4.1.2-4.1.4 take MPI_MIN / MPI_MAX of
    // MPI_UNSIGNED_LONG (std::uint64_t here) as signed (open-mpi/ompi#10525, #10648), which
    // would make the sentinel kInvalidUid the smallest.
    auto const smallest = static_cast<Uid>(comm.allReduce<unsigned long long>(
        first < entries.size() ? entries[first].uid : kInvalidUid, core::ReduceOp::Min));
    auto const root = static_cast<int>(smallest % ranks);
    std::string msg;
    if (comm.rank() == root) {
        msg = fmt::format("particle uid {} is a master twice, at {} and at {}: a grain inserted "
                          "twice with the same uid",
                          smallest, describe(entries[first]), describe(entries[first + 1]));
        if (total > 1)
            msg += fmt::format(" ({} more uids are duplicated)", total - 1);
    }
    comm.broadcast(msg, root);
    throw core::InputError(msg);
}

} // namespace regolith::particles
