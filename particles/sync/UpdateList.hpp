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
/// check, Neighbor::decide, compares every atom every step instead). One rank: every
/// shadow's master is in this process.
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/SyncMethod.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace regolith::particles {

class UpdateList {
public:
    /// The list for `config` on a communicator of `ranks` ranks: none without a skin. Throws
    /// core::InputError (the same on every rank) if the skin is negative or not finite, the
    /// method is SOS, or there is more than one rank.
    static std::unique_ptr<UpdateList> forConfig(SyncConfig const& config, int ranks);

    /// Records what the full synchronisation left in `local`: per block, every copy's position
    /// (the masters' are the references) and, per shadow, its master; a master may move
    /// `budget` from its reference before the list stops holding. Leaves the list invalid if
    /// some copy is SOS class (Flag::Spreads) or some shadow's master is not on rank `rank`.
    void rebuild(LocalParticles const& local, int rank, double budget);

    enum class Verdict {
        Holds,   ///< every master within the budget of its reference and inside its block
        Leavers, ///< within the budget, but some masters left their blocks (leavers())
        Refresh, ///< invalid, a storage changed (add, remove, re-key), or a master moved too far
    };
    /// Where `local` stands against the list, given that no master moved more than
    /// `movedAtMost` since the last check() or rebuild() (+inf if unknown). Local; O(copies)
    /// without a bound, O(masters near a face) with one.
    [[nodiscard]] Verdict check(LocalParticles const& local, double movedAtMost);
    /// After check() said Leavers: per block, the masters that left it, ascending.
    [[nodiscard]] std::vector<std::vector<std::uint32_t>> const& leavers() const {
        return m_leavers;
    }
    /// The budget left after a partial refresh: the masters that did not leave keep their
    /// shadows, decided within `budget` of positions that are now up to the largest
    /// displacement check() saw away (triangle inequality).
    [[nodiscard]] double budgetLeft() const { return m_budget - m_largestMove; }

    /// Copies every master's motion and contact history to its shadows, as Alg. 1's update
    /// does (flags and owner stay as the refresh left them: nothing changes them between
    /// refreshes); returns the number of shadows updated. Pre: check() said Holds or Leavers,
    /// and no storage changed since.
    std::size_t update(LocalParticles& local) const;

    /// ParticleSync::reduceForces' in-place path along the list: adds every shadow's force and
    /// torque and its history entries stamped `stamp` to its master and zeroes the shadow's
    /// force and torque. Returns false, doing nothing, unless the list is valid and no storage
    /// changed since rebuild().
    bool reduce(LocalParticles& local, std::uint32_t stamp) const;

private:
    [[nodiscard]] bool unchanged(LocalParticles const& local) const;

    struct Shadow {
        std::uint32_t index = 0;       ///< in its block's storage
        std::uint32_t masterBlock = 0; ///< index into local.blocks()
        std::uint32_t master = 0;      ///< in that block's storage
    };
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
    int m_rank = 0;
    bool m_valid = false;
};

} // namespace regolith::particles
