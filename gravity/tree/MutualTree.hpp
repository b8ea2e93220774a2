#pragma once
/// Momentum-conserving tree gravity (beyond the papers): the mutual dual-tree walk
/// of Dehnen (2002, "A hierarchical O(N) force calculation algorithm", J. Comput. Phys. 179,
/// 27; the falcON scheme). Cells interact with cells; each interaction computes the force
/// between two cells once, from the interaction energy
///   E(R) = -G [M_A M_B / R + Rᵀ(M_A Q_B + M_B Q_A)R / (2 R⁵)],  R = com_A - com_B,
/// and applies it to A and, negated, to B, so Newton's third law holds interaction by
/// interaction and the total force vanishes to round-off: an isolated system's centre of
/// mass does not drift (the plain Barnes–Hut tree lets it drift, since the force of cell B on
/// grain a is not the negative of cell A's on grain b).
///
/// The field a cell receives is stored as a first-order Taylor expansion about its centre
/// of mass (acceleration + tidal tensor of the monopole) and passed down to the grains.
/// Passing it down keeps momentum exact too: Σ m_i T (x_i - com) = 0.
///
/// Serial kernel: one rank evaluates all grains. evaluateGathered() runs it in parallel by
/// gathering every grain on every rank (redundant work; no speed-up with ranks).
#include "core/mpi/Comm.hpp"
#include "gravity/common/PointMasses.hpp"
#include "gravity/tree/TreeOptions.hpp"

namespace regolith::gravity::tree {

struct MutualStats {
    long long cellCell = 0;  ///< accepted cell–cell interactions
    long long grainPair = 0; ///< grain–grain pairs evaluated directly
};

class MutualTree {
public:
    /// Validates `options` (core::InputError naming the key). Uses θ, G, softening,
    /// quadrupole and leafSize; two cells interact as multipoles when
    /// θ |com_A - com_B| > b_max,A + b_max,B.
    explicit MutualTree(TreeOptions const& options);

    /// Field at every grain due to all other grains; overwrites `out`. Returns ½ Σ m φ in J.
    /// Throws core::InputError for bad masses. Not collective.
    double evaluate(PointMasses const& grains, FieldOut out);

    /// The same over all ranks' grains, gathered on every rank; `out` receives the local
    /// grains' field. Returns the total ½ Σ m φ. COLLECTIVE over `comm`.
    double evaluateGathered(core::Comm const& comm, PointMasses const& local, FieldOut out);

    [[nodiscard]] MutualStats const& stats() const { return m_stats; }

private:
    TreeOptions m_options;
    MutualStats m_stats;
};

} // namespace regolith::gravity::tree
