#pragma once
/// The particles of one rank: one ParticleStorage per local block of the forest. A block
/// holds the masters whose centre it contains and a shadow (read-only copy) of every other
/// particle that overlaps it, at the periodic image through which it overlaps (CopyImage).
#include "domain/Block.hpp"
#include "domain/BlockForest.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/sync/SentCache.hpp"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace regolith::particles {

struct BlockParticles {
    domain::Block const* block = nullptr;
    ParticleStorage particles;
    SentCache sent; ///< SOS: creation orders this block sent (SentCache.hpp)
    /// A master and where it was when listed (the index is a hint: round 1 may move it).
    struct MasterHint {
        Uid uid = kInvalidUid;
        std::size_t index = 0;
    };
    /// ParticleSync's work list within one call: the SOS-class masters of this block that
    /// may reach beyond it (not deep inside after the first round, or promoted here in it),
    /// so that the second round visits them without a pass over every master.
    std::vector<MasterHint> spreadingMasters;
};

/// A number per copy of each local block (blocks() order, then storage order): the contacts of
/// a copy, for the load balance's model (coupling/balance/BlockWeights.hpp).
using ContactCounts = std::vector<std::vector<std::uint32_t>>;

/// All local blocks' particles, in the order of forest.blocks().
class LocalParticles {
public:
    /// One empty storage per local block of `forest` (which must outlive this object).
    explicit LocalParticles(domain::BlockForest const& forest);

    [[nodiscard]] domain::BlockForest const& forest() const { return *m_forest; }
    /// The domain's extent along the axes where the particles keep no image (wrappedAxes), 0
    /// on the others: each storage's ParticleStorage::wrapPeriod.
    [[nodiscard]] core::Vec3 wrapPeriod() const;
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

    /// What a leaf (forest block) holds: its masters, and their contacts (each counted once:
    /// a pair's lives on one of its grains, a wall's on the grain).
    struct LeafLoad {
        std::size_t grains = 0;
        std::size_t contacts = 0;
    };
    /// Per leaf local block b covers (domain::Block::leaves, in that order): the load of each
    /// forest block, where the particles' blocks merge several, with `contacts[i]` the
    /// contacts of copy i of block b (none given: the grains only).
    [[nodiscard]] std::vector<LeafLoad>
    loadPerLeaf(std::size_t b, std::span<std::uint32_t const> contacts = {}) const;
    /// Each master's contact-history entries stamped `stamp` (ContactCounts): its contacts of
    /// the force computation of that number (a step's; a checkpoint's grains carry those of
    /// its last step). Entries of contacts broken since are not counted.
    [[nodiscard]] ContactCounts contactsStamped(std::uint32_t stamp) const;
    /// Throws core::Error unless `counts` holds a number for every copy of every local block,
    /// as the storages are now: counts taken before a synchronisation or a move changed them
    /// would be read for other grains, or past their end.
    void requireCountsCover(ContactCounts const& counts) const;

    /// Masters / all copies on this rank.
    [[nodiscard]] std::size_t countMasters() const;
    [[nodiscard]] std::size_t countCopies() const;

private:
    domain::BlockForest const* m_forest;
    std::vector<BlockParticles> m_blocks;
    std::vector<std::pair<std::uint64_t, std::size_t>> m_byId; ///< (raw id, index), sorted
};

} // namespace regolith::particles
