#pragma once
/// The cell grid of grid gravity on an unrefined block forest: every block holds n[0] x n[1]
/// x n[2] interior cells plus `ghost` layers, and the cells of all blocks form one uniform
/// global grid of rootBlocks[a] * n[a] cells per axis. Also answers "who owns global cell c"
/// for any cell of the domain (a small table of every block's owner and curve position,
/// gathered once), which deposition and the Poisson matrix need for cells beyond the
/// neighbour blocks.
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace regolith::gravity {

/// Index of a cell in the global grid; may lie outside [0, globalCells) before wrapping.
using GlobalCell = std::array<std::int64_t, 3>;

/// Where an interior cell lives.
struct CellOwner {
    int rank = -1;            ///< owner rank of the block
    std::int64_t row = -1;    ///< global row: curveIndex * cellsPerBlock + interior index
    int localBlock = -1;      ///< index into forest.blocks() if this rank owns it, else -1
    std::size_t interior = 0; ///< interior index (i + n0 * (j + n1 * k)) in its block
    std::size_t pad = 0;      ///< padded index of that cell (padOfInterior(interior))
};

class CellLayout {
public:
    /// Pre: `forest` outlives this object. Throws core::InputError (on every rank alike) if
    /// the forest is refined ("domain.refine"), a component of cellsPerBlock is < 1 or smaller
    /// than the ghost width ("domain.cells_per_block"), or ghost is not 1 or 2.
    /// COLLECTIVE over `comm` (one all-gather of the block table; O(global blocks) memory).
    CellLayout(core::Comm const& comm, domain::BlockForest const& forest,
               std::array<int, 3> cellsPerBlock, int ghost);

    [[nodiscard]] domain::BlockForest const& forest() const { return *m_forest; }
    [[nodiscard]] std::array<int, 3> const& cellsPerBlock() const { return m_n; }
    [[nodiscard]] int ghost() const { return m_ghost; }
    /// Interior cells of one block.
    [[nodiscard]] std::size_t cellsInBlock() const { return m_cellsInBlock; }
    /// Cells of one block including ghost layers.
    [[nodiscard]] std::size_t paddedCellsInBlock() const { return m_paddedCells; }
    /// Padded extent per axis: n[a] + 2 ghost.
    [[nodiscard]] std::array<int, 3> const& padded() const { return m_padded; }
    /// Cells per axis over the whole domain.
    [[nodiscard]] std::array<std::int64_t, 3> const& globalCells() const { return m_global; }
    [[nodiscard]] std::int64_t globalCellCount() const {
        return m_global[0] * m_global[1] * m_global[2];
    }
    /// Cell size per axis [length].
    [[nodiscard]] core::Vec3 const& spacing() const { return m_h; }
    [[nodiscard]] double cellVolume() const { return m_h.prod(); }
    [[nodiscard]] std::size_t localBlockCount() const { return m_origins.size(); }
    /// Global cell of interior cell (0,0,0) of local block b.
    [[nodiscard]] GlobalCell const& origin(std::size_t b) const { return m_origins[b]; }
    /// Global row of interior cell 0 of local block b (rows are numbered block by block along
    /// the curve, so this rank's rows are one contiguous range, as PETSc wants).
    [[nodiscard]] std::int64_t firstRow(std::size_t b) const;
    /// This rank's row range [begin, end) (empty for an idle rank).
    [[nodiscard]] std::int64_t rowBegin() const { return m_rowBegin; }
    [[nodiscard]] std::int64_t rowEnd() const {
        return m_rowBegin + static_cast<std::int64_t>(localBlockCount() * m_cellsInBlock);
    }

    /// Linear index of padded cell (i, j, k), each in [-ghost, n + ghost).
    [[nodiscard]] std::size_t padIndex(int i, int j, int k) const {
        return static_cast<std::size_t>(i + m_ghost) +
               static_cast<std::size_t>(m_padded[0]) *
                   (static_cast<std::size_t>(j + m_ghost) +
                    static_cast<std::size_t>(m_padded[1]) * static_cast<std::size_t>(k + m_ghost));
    }
    /// Padded index of interior index `interior` (a table: hot loops over all cells).
    [[nodiscard]] std::size_t padOfInterior(std::size_t interior) const {
        return m_padOfInterior[interior];
    }

    /// Maps c into the grid on periodic axes; nullopt if outside on a non-periodic axis.
    [[nodiscard]] std::optional<GlobalCell> wrap(GlobalCell c) const;
    /// Owner of global cell c (wrapped first); nullopt outside the domain. Local, O(1).
    [[nodiscard]] std::optional<CellOwner> owner(GlobalCell const& c) const;
    /// Local block index of a row owned by this rank, and the interior index. Pre: row in
    /// [rowBegin, rowEnd).
    [[nodiscard]] std::pair<std::size_t, std::size_t> localOfRow(std::int64_t row) const;
    /// Centre of global cell c [length] (no wrapping: ghost and image cells allowed).
    [[nodiscard]] core::Vec3 centre(GlobalCell const& c) const;
    /// Continuous cell coordinate of p: cell centres at integers, (p - min) / h - 1/2.
    [[nodiscard]] core::Vec3 cellCoordinate(core::Vec3 const& p) const;

private:
    domain::BlockForest const* m_forest;
    std::array<int, 3> m_n;
    int m_ghost;
    std::array<int, 3> m_padded{};
    std::size_t m_cellsInBlock = 0;
    std::size_t m_paddedCells = 0;
    std::array<std::int64_t, 3> m_global{};
    core::Vec3 m_h;
    std::vector<GlobalCell> m_origins;
    std::vector<std::uint32_t> m_padOfInterior;
    std::int64_t m_rowBegin = 0;
    std::size_t m_firstCurve = 0;
    /// Per root block (root index): owner rank and curve index.
    std::vector<int> m_ownerOfRoot;
    std::vector<std::int64_t> m_curveOfRoot;
};

} // namespace regolith::gravity
