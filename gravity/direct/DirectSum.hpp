#pragma once
/// Exact pairwise self-gravity over all masters on all ranks: the reference for every
/// accuracy figure of the tree and grid methods.
///
/// Parallel scheme: a ring pass (the "systolic" all-pairs scheme). Every rank packs its
/// grains into one block; in P steps each block visits every rank, which adds the block's
/// field to its own grains. O(N²/P) work and O(N) traffic per rank; the next block is
/// received while the current one is evaluated.
///
/// Reproducible mode instead gathers every grain on every rank and sums each target's sources
/// in one order, by the bits of their (x, y, z, m): the same operations on any number of
/// ranks, so the same bits even where the field cancels (the centre of a symmetric pile, where
/// the double-double sum's error, small against the largest term, is the whole result).
#include "core/mpi/Comm.hpp"
#include "gravity/common/PointMasses.hpp"

#include <vector>

namespace regolith::gravity::direct {

struct DirectOptions {
    double G = kNewtonG;       ///< m³ kg⁻¹ s⁻²
    double softening = 0.0;    ///< Plummer softening length ε in m (0: exact Newton)
    bool reproducible = false; ///< sources in one order on any ranks (see above)
};

/// Throws core::InputError naming `gravity.G` / `gravity.softening` if G <= 0 or ε < 0 (or
/// either is not finite).
void validate(DirectOptions const& options);

/// Field at `targets` (their masses unused) due to every grain of `sources`, summed in
/// double-double (DirectKernel.hpp); a target at zero distance from a source (itself)
/// ignores that source. Overwrites `out`. Returns ½ Σ m_t φ_t over the targets, in J (the
/// potential energy of the targets if targets and sources are the same set). Not collective.
double directSumSerial(PointMasses const& targets, PointMasses const& sources, FieldOut out,
                       DirectOptions const& options);

/// The distributed direct sum; owns a duplicate of the communicator.
class DirectSum {
public:
    /// COLLECTIVE over `comm` (duplicates it). Validates `options` (InputError).
    DirectSum(core::Comm const& comm, DirectOptions const& options);

    /// Field at every local grain due to every grain on every rank. Overwrites `out` (size of
    /// `local`). Forces agree across rank counts to far below 1e-12, and bit for bit in
    /// reproducible mode. Returns the total potential energy ½ Σ m φ over all ranks, in J.
    /// Throws core::InputError (on every rank) if any rank has a negative mass or a
    /// non-finite position. COLLECTIVE over the communicator.
    double evaluate(PointMasses const& local, FieldOut out);

    [[nodiscard]] DirectOptions const& options() const { return m_options; }

private:
    core::Comm m_comm;
    DirectOptions m_options;
};

} // namespace regolith::gravity::direct
