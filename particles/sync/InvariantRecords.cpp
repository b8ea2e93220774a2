#include "particles/sync/InvariantRecords.hpp"

#include "core/Error.hpp"
#include "core/mpi/Buffer.hpp"

#include <cstddef>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace regolith::particles::sync_detail {

std::string packLocal(LocalParticles const& local) {
    core::SendBuffer b;
    b << static_cast<std::uint64_t>(local.blocks().size());
    for (BlockParticles const& bp : local.blocks()) {
        ParticleStorage const& ps = bp.particles;
        b << bp.block->id.raw() << bp.block->aabb.min << bp.block->aabb.max
          << static_cast<std::uint64_t>(ps.size());
        for (std::size_t i = 0; i < ps.size(); ++i) {
            b << ps.uid(i) << ps.image(i) << ps.flags(i) << ps.owner(i) << ps.position(i)
              << ps.velocity(i) << ps.angularVelocity(i) << ps.orientation(i) << ps.radius(i)
              << ps.mass(i);
            if (ps.flags(i).isMaster())
                b << ps.shadowHolders(i).vector();
        }
    }
    auto const bytes = b.bytes();
    return {reinterpret_cast<char const*>(bytes.data()), bytes.size()};
}

void unpackRank(int rank, std::string const& s, std::vector<CopyRecord>& copies,
                std::vector<std::pair<std::uint64_t, BlockRecord>>& blocks) {
    std::vector<std::byte> data(s.size());
    if (!s.empty())
        std::memcpy(data.data(), s.data(), s.size());
    core::RecvBuffer in(std::move(data));
    auto const nBlocks = core::read<std::uint64_t>(in);
    for (std::uint64_t b = 0; b < nBlocks; ++b) {
        std::uint64_t id = 0;
        BlockRecord block{rank, {}};
        std::uint64_t n = 0;
        in >> id >> block.box.min >> block.box.max >> n;
        blocks.emplace_back(id, block);
        for (std::uint64_t i = 0; i < n; ++i) {
            CopyRecord& c = copies.emplace_back();
            c.rank = rank;
            c.block = id;
            in >> c.uid >> c.image >> c.flags >> c.owner >> c.position >> c.velocity >>
                c.angularVelocity >> c.orientation >> c.radius >> c.mass;
            if (c.flags.isMaster())
                in >> c.holders;
        }
    }
    if (!in.exhausted())
        throw core::BufferError("checkSyncInvariants: trailing bytes in rank " +
                                std::to_string(rank) + "'s record");
}

} // namespace regolith::particles::sync_detail
