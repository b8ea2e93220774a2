#pragma once
/// What checkSyncInvariants (SyncInvariants.hpp) gathers on rank 0: a record of every copy and
/// of every block box, packed per rank and unpacked there.
#include "core/math/AABB.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/sync/BlockParticles.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace regolith::particles::sync_detail {

/// What rank 0 learns about one copy.
struct CopyRecord {
    int rank = -1;
    std::uint64_t block = 0;
    Uid uid = kInvalidUid;
    CopyImage image = kNoImage;
    Flags flags{};
    BlockRef owner{};
    core::Vec3 position = core::Vec3::Zero();
    core::Vec3 velocity = core::Vec3::Zero();
    core::Vec3 angularVelocity = core::Vec3::Zero();
    core::Quat orientation = core::Quat::Identity();
    double radius = 0.0;
    double mass = 0.0;
    std::vector<CopyRef> holders; ///< masters only

    [[nodiscard]] CopyRef where() const { return {rank, block, image}; }
};

struct BlockRecord {
    int rank = -1;
    core::AABB box;
};

/// This rank's blocks and copies, packed for the gather.
std::string packLocal(LocalParticles const& local);
/// Appends what rank `rank` packed in `s` to `copies` and `blocks` (block id, record). Throws
/// core::BufferError on trailing bytes.
void unpackRank(int rank, std::string const& s, std::vector<CopyRecord>& copies,
                std::vector<std::pair<std::uint64_t, BlockRecord>>& blocks);

} // namespace regolith::particles::sync_detail
