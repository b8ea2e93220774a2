#pragma once
/// The particles of one rank: one ParticleStorage per local block of the forest. A block
/// holds the masters whose centre it contains and a shadow (read-only copy) of every other
/// particle that overlaps it, at the periodic image through which it overlaps (CopyImage).
#include "domain/Block.hpp"
#include "domain/BlockForest.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <cstdint>
#include <set>
#include <span>
#include <tuple>
#include <vector>

namespace regolith::particles {

/// SOS's per-block cache (Eibl & Ruede 2018, sec. 3.3): the copies this block has already
/// ordered its neighbours to create, so that a copy does not re-send creation orders every
/// call. An entry is forgotten when the target block reports that it dropped the copy, or
/// when this block drops its own copy of the particle.
struct SentEntry {
    std::uint64_t block = 0; ///< the neighbour block (BlockId::raw)
    Uid uid = kInvalidUid;
    CopyImage image = kNoImage; ///< the image of the copy on the neighbour
    friend auto operator<=>(SentEntry const&, SentEntry const&) = default;
};

struct BlockParticles {
    domain::Block const* block = nullptr;
    ParticleStorage particles;
    std::set<SentEntry> sent;
};

/// All local blocks' particles, in the order of forest.blocks().
class LocalParticles {
public:
    /// One empty storage per local block of `forest` (which must outlive this object).
    explicit LocalParticles(domain::BlockForest const& forest);

    [[nodiscard]] domain::BlockForest const& forest() const { return *m_forest; }
    [[nodiscard]] std::span<BlockParticles> blocks() { return m_blocks; }
    [[nodiscard]] std::span<BlockParticles const> blocks() const { return m_blocks; }
    /// The local block with this raw id, or nullptr.
    [[nodiscard]] BlockParticles* find(std::uint64_t blockId);
    [[nodiscard]] BlockParticles const* find(std::uint64_t blockId) const;

    /// Adds a new master to the local block whose box contains `p.position` (after wrapping
    /// on periodic axes). Returns false if no local block contains it (another rank's, or
    /// outside the domain). Shadows appear at the next synchronisation. Throws core::Error
    /// if the uid is already a master here.
    bool addMaster(ParticleInit p);

    /// Adds every copy of `masters` as a master (addMaster; throws core::Error naming the
    /// first uid no local block contains). If this rank has one block and every copy is
    /// already a master of it (owner, position in its box, no image), the storage is moved in
    /// whole instead of copied: the set-up then holds the grains once, not twice.
    void adoptMasters(ParticleStorage&& masters);

    /// Masters / all copies on this rank.
    [[nodiscard]] std::size_t countMasters() const;
    [[nodiscard]] std::size_t countCopies() const;

private:
    domain::BlockForest const* m_forest;
    std::vector<BlockParticles> m_blocks;
};

} // namespace regolith::particles
