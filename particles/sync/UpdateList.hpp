#pragma once
/// Shadow updates along a list fixed between refreshes (SyncConfig::skin > 0): LAMMPS's scheme
/// for ghost atoms -- decide at a neighbour-list rebuild, with a skin, which atoms need a ghost,
/// then only copy along the fixed send lists until the next rebuild -- applied to the NNS class
/// of Eibl & Ruede 2018's Alg. 1.
///
/// Why the trajectories stay Alg. 1's. At a full decision the synchronisation ran with every
/// NNS-class grain's radius grown by the skin s: a master has a shadow in every block image
/// where copyNeeded(box, x_ref, r + s) holds, and nowhere else. While every master stays within
/// s of x_ref (check() before each call), where it has no shadow its ball of radius r still
/// reaches no block (distance > r + s - s), and where it had one the shadow is still there:
/// every copy Alg. 1 needs exists, plus some Alg. 1 would have removed (all within r + 2 s).
/// Masters that leave their blocks are decided alone by Alg. 1, at their new position; the
/// others keep their shadows, and the budget left to all shrinks by the largest displacement
/// seen (triangle inequality), so ownership stays Alg. 1's. A contact is evaluated by the block
/// holding its ownership point whatever extra copies exist, so the forces are the same; in
/// reproducible mode the trajectories are identical bit for bit (tests/apps/SyncEquality.cmake,
/// tests/particles/sync/UpdateListTest.cpp).
///
/// Cost per call: one copy per shadow, where Alg. 1 scans every copy, decides for each master
/// near a face and looks each shadow up in the (uid, image) index, and the force reduction
/// looks each master up again; plus, if the caller knows no bound on the masters' motion since
/// the last call, one branch-free pass over the copies (displacement and containment). With a
/// bound (the integrator's largest move, DemStep) the displacements are not compared: their
/// sum since the refresh bounds every master's, and only the masters that were within twice
/// the budget of a block face at the refresh can have left their block (LAMMPS's neighbour
/// check, Neighbor::decide, compares every atom every step instead).
///
/// Several ranks. A shadow whose master is on another rank is updated from a message along
/// the same fixed list: at a refresh each rank sends the owners of its remote shadows their
/// keys (owner block, uid) in its own storage order, once; until the next refresh the owner
/// sends those masters' motion and history in that order, and receives back the forces,
/// torques and touched history entries of the shadows that have any, by their place in it
/// (LAMMPS's send lists, Comm::borders then forward_comm / reverse_comm). No decision,
/// look-up or key per call. Whether the list holds is decided by every rank together (agree(),
/// or a reduction of the caller's: the most demanding verdict wins), since a refresh is
/// collective.
#include "core/mpi/Comm.hpp"
#include "core/mpi/CommCounters.hpp"
#include "core/mpi/NeighbourExchange.hpp"
#include "domain/BlockForest.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/SyncMethod.hpp"
#include "particles/sync/SyncVerdict.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace regolith::particles {

class UpdateList {
public:
    /// The list for `config` over `forest` on `comm`: none without a skin. Throws
    /// core::InputError (the same on every rank) if the skin is negative or not finite or the
    /// method is SOS. COLLECTIVE over `comm` (the exchange with the neighbour blocks' ranks).
    static std::unique_ptr<UpdateList> forConfig(SyncConfig const& config, core::Comm const& comm,
                                                 domain::BlockForest const& forest);

    /// COLLECTIVE over `comm`; `peers`: the other ranks this one may share a grain with
    /// (symmetric, as BlockForest::neighbourRanks).
    UpdateList(core::Comm const& comm, std::vector<int> peers);

    /// Records what the full synchronisation left in `local`: per block, every copy's position
    /// (the masters' are the references) and, per shadow, its master (on this rank, or the
    /// owner's send list, exchanged here); a master may move `budget` from its reference
    /// before the list stops holding. Leaves the list invalid if some copy is SOS class
    /// (Flag::Spreads) or some shadow's master cannot be found. Adds the traffic to `stats`.
    /// COLLECTIVE.
    void rebuild(LocalParticles const& local, double budget, core::CommStats& stats);

    /// After a call that synchronised the leavers only (check() said Leavers): brings the list
    /// up to date with what that call changed -- the slots named by the storages' trace
    /// journals (ParticleStorage::startTracing) and the leavers' own -- instead of a pass over
    /// every copy. The lists of shadows come out as rebuild() would leave them; the budget and
    /// the references of the copies not changed stay (the masters decided now at their
    /// positions now, with the whole skin). A rank with a storage not traced, or that meets an
    /// SOS-class copy or a shadow without its master, rebuilds (rebuild(local, budgetLeft())).
    /// Adds the traffic to `stats`; returns whether it followed (false: rebuilt). COLLECTIVE
    /// (the key exchange, as rebuild()).
    bool followLeavers(LocalParticles const& local, core::CommStats& stats);

    /// SyncVerdict.hpp; agree() takes the maximum over the ranks.
    using Verdict = SyncVerdict;
    static constexpr int kIdleCalls = 32;
    static constexpr int kMaxIdleCalls = 1024;
    /// Where `local` stands against the list, given that no master moved more than
    /// `movedAtMost` since the last check() or rebuild() (+inf if unknown); Idle while idle
    /// calls are left (counting this one). Local; O(copies) without a bound, O(blocks + masters
    /// near a face) with one.
    [[nodiscard]] Verdict check(LocalParticles const& local, double movedAtMost);
    /// The verdict every rank acts on: the most demanding of the ranks' check(). A rank whose
    /// own was Holds acts on Leavers with no leavers of its own. COLLECTIVE (one all-reduce,
    /// none on one rank).
    [[nodiscard]] Verdict agree(Verdict own) const;
    /// After check() said Leavers: per block, the masters that left it, ascending.
    [[nodiscard]] std::vector<std::vector<std::uint32_t>> const& leavers() const {
        return m_leavers;
    }
    /// Marks the list invalid (after a call that did not refresh it, e.g. an Idle one).
    void invalidate() { m_valid = false; }
    /// The budget left after a partial refresh: the masters that did not leave keep their
    /// shadows, decided within `budget` of positions that are now up to the largest
    /// displacement check() saw away (triangle inequality).
    [[nodiscard]] double budgetLeft() const { return m_budget - m_largestMove; }

    /// Copies every master's motion and contact history to its shadows, as Alg. 1's update
    /// does (flags and owner stay as the refresh left them: nothing changes them between
    /// refreshes); returns the number of shadows updated here. Adds the traffic to `stats`.
    /// Pre: the ranks agreed on Holds or Leavers, and no storage changed since. COLLECTIVE.
    std::size_t update(LocalParticles& local, core::CommStats& stats);

    /// Lets each shadow listed here whose master lies in the same storage use its master's
    /// contact history (ParticleStorage::shareHistories), while the layouts stay: update()
    /// then copies no history to it and reduce() takes none from it. Nothing if not valid;
    /// returns whether valid. Local.
    bool shareHistories(LocalParticles& local) const;

    /// Whether the list holds here for the force reduction: valid, and no storage changed
    /// since rebuild(). Local.
    [[nodiscard]] bool holds(LocalParticles const& local) const;
    /// ParticleSync::reduceForces' in-place path along the list: adds every shadow's force and
    /// torque and its history entries stamped `stamp` to its master and zeroes the shadow's
    /// force and torque. `everywhere`: whether holds() on every rank (the caller's reduction);
    /// returns it, doing nothing if false. Throws core::Error if `everywhere` but not holds()
    /// here (a storage changed after the caller's reduction). Adds the traffic to `stats`.
    /// COLLECTIVE.
    bool reduce(LocalParticles& local, std::uint32_t stamp, core::CommStats& stats,
                bool everywhere);

private:
    struct Shadow {
        std::uint32_t index = 0;       ///< in its block's storage
        std::uint32_t masterBlock = 0; ///< index into local.blocks()
        std::uint32_t master = 0;      ///< in that block's storage
    };
    /// A copy on this rank: index into local.blocks(), index in that block's storage.
    struct CopyAt {
        std::uint32_t block = 0;
        std::uint32_t index = 0;
    };
    /// What names a master to its owner: its block's raw id and its uid.
    struct Key {
        std::uint64_t block = 0;
        Uid uid = kInvalidUid;
    };

    /// The local blocks by raw id, ascending (id, index into local.blocks()).
    using BlocksById = std::vector<std::pair<std::uint64_t, std::uint32_t>>;
    static BlocksById blocksById(LocalParticles const& local);
    /// Where the master `uid` of local block `blockId` is: (block index, storage index), or
    /// false.
    static bool findMaster(LocalParticles const& local, BlocksById const& byId,
                           std::uint64_t blockId, Uid uid, std::uint32_t& block,
                           std::uint32_t& index);
    /// Whether a master at `x` may leave `box` by moving less than `budget`.
    static bool mayLeave(core::AABB const& box, core::Vec3 const& x, double budget);
    /// followLeavers() without the key exchange; false if this rank must rebuild instead.
    bool followStorages(LocalParticles const& local, BlocksById const& byId,
                        std::vector<std::vector<Key>>& keys);

    /// rebuild()'s exchange: sends each owner the keys of this rank's remote shadows (m_from)
    /// and turns the keys received into m_to (`byId`: the local blocks by raw id, ascending).
    /// False if some key names no master here.
    bool exchangeKeys(LocalParticles const& local, BlocksById const& byId,
                      std::vector<std::vector<Key>> const& keys, core::CommStats& stats);
    /// Index of `rank` in the exchange's peers, or -1.
    [[nodiscard]] int peerSlot(int rank) const;

    struct BlockState {
        std::uint64_t revision = 0;        ///< ParticleStorage::layoutRevision at rebuild()
        std::vector<core::Vec3> reference; ///< every copy's position at rebuild()
        std::vector<Shadow> shadows;
        /// The masters within twice the budget of a block face at rebuild(), ascending: with
        /// a bound on the motion, the only ones that may have left the block.
        std::vector<std::uint32_t> nearFaces;
    };
    std::vector<BlockState> m_blocks; ///< per local block
    std::vector<std::vector<std::uint32_t>> m_leavers;
    double m_budget = 0.0;
    double m_largestMove = 0.0; ///< bound on a master's distance from its reference (check())
    /// The bound at the last followLeavers(): the copies moved to another slot since the
    /// refresh have their reference there, up to this far from the true one.
    double m_followedMove = 0.0;
    core::Comm m_comm;                                   ///< a duplicate of the run's
    std::unique_ptr<core::NeighbourExchange> m_exchange; ///< with the peers; none on one rank
    std::vector<std::vector<CopyAt>> m_from; ///< per peer: its masters' shadows here, in order
    std::vector<std::vector<CopyAt>> m_to;   ///< per peer: masters here with shadows there
    bool m_valid = false;
    int m_idleCalls = 0; ///< Idle verdicts left (set by a refresh that met an SOS-class copy)
    int m_idleLength = kIdleCalls; ///< the Idle verdicts the next such refresh sets
};

} // namespace regolith::particles
