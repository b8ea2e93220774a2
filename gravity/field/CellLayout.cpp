#include "gravity/field/CellLayout.hpp"

#include "core/Error.hpp"
#include "core/memory/MemoryBudget.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

namespace regolith::gravity {

namespace {

void validate(domain::BlockForest const& forest, std::array<int, 3> const& n, int ghost) {
    if (forest.maxLevel() != 0)
        throw core::InputError(fmt::format(
            "domain.refine: grid gravity needs an unrefined forest (cells of one size), but the "
            "forest is refined to level {}",
            forest.maxLevel()));
    if (ghost < 1 || ghost > 2)
        throw core::Error(fmt::format("grid gravity: ghost width must be 1 or 2, got {}", ghost));
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) // the scene's default: no grid
        throw core::InputError("domain.cells_per_block: required with grid gravity (pm, p3m): "
                               "the cells of every block per axis, e.g. [16, 16, 16]");
    for (int a = 0; a < 3; ++a)
        if (n[a] < 1 || n[a] < ghost)
            throw core::InputError(fmt::format(
                "domain.cells_per_block: grid gravity needs at least {} cell(s) per block and "
                "axis (the ghost width), got {}",
                ghost, n));
}

} // namespace

CellLayout::CellLayout(core::Comm const& comm, domain::BlockForest const& forest,
                       std::array<int, 3> cellsPerBlock, int ghost)
    : m_forest(&forest)
    , m_n(cellsPerBlock)
    , m_ghost(ghost) {
    validate(forest, cellsPerBlock, ghost);
    // Before anything is sized by it: the fields (5 doubles a cell) and PETSc's matrix and
    // vectors (~100 bytes a row) of this rank's share, alike on every rank.
    double globalCells = 1.0;
    for (int a = 0; a < 3; ++a)
        globalCells *= static_cast<double>(forest.rootBlocks()[a]) * cellsPerBlock[a];
    core::requireMemory(globalCells / comm.size() * 140.0, "domain.cells_per_block",
                        fmt::format("a grid of {:.3g} cells", globalCells));
    auto const& geo = forest.geometry();
    for (int a = 0; a < 3; ++a) {
        m_padded[a] = m_n[a] + 2 * ghost;
        m_global[a] = static_cast<std::int64_t>(forest.rootBlocks()[a]) * m_n[a];
        m_h[a] = forest.domain().extent()[a] / static_cast<double>(m_global[a]);
    }
    m_cellsInBlock = static_cast<std::size_t>(m_n[0]) * static_cast<std::size_t>(m_n[1]) *
                     static_cast<std::size_t>(m_n[2]);
    m_paddedCells = static_cast<std::size_t>(m_padded[0]) * static_cast<std::size_t>(m_padded[1]) *
                    static_cast<std::size_t>(m_padded[2]);
    m_padOfInterior.reserve(m_cellsInBlock);
    for (int k = 0; k < m_n[2]; ++k)
        for (int j = 0; j < m_n[1]; ++j)
            for (int i = 0; i < m_n[0]; ++i)
                m_padOfInterior.push_back(static_cast<std::uint32_t>(padIndex(i, j, k)));

    // Every rank learns every block's owner and curve position: the forest keeps only the
    // neighbours, but a large grain deposits into blocks further away, and the Poisson
    // matrix numbers rows by curve position. 16 bytes per block, gathered once.
    std::vector<std::int64_t> mine; // pairs (root index, curve index)
    for (auto const& b : forest.blocks()) {
        auto const root = b.id.rootIndex();
        auto const c = geo.rootCoord(root);
        m_origins.push_back({c[0] * m_n[0], c[1] * m_n[1], c[2] * m_n[2]});
        mine.push_back(static_cast<std::int64_t>(root));
        mine.push_back(static_cast<std::int64_t>(b.curveIndex));
    }
    if (!forest.blocks().empty()) {
        m_firstCurve = forest.blocks().front().curveIndex;
        m_rowBegin = static_cast<std::int64_t>(m_firstCurve * m_cellsInBlock);
    }
    std::vector<int> counts;
    std::vector<std::int64_t> const all = comm.allGatherVarying<std::int64_t>(mine, &counts);
    auto const roots = static_cast<std::size_t>(geo.rootCount());
    m_ownerOfRoot.assign(roots, -1);
    m_curveOfRoot.assign(roots, -1);
    int begin = 0; // rank r's pairs: [begin, begin + counts[r]) of `all`
    for (std::size_t r = 0; r < counts.size(); begin += counts[r], ++r)
        for (int i = begin; i < begin + counts[r]; i += 2) {
            auto const root = static_cast<std::size_t>(all[static_cast<std::size_t>(i)]);
            m_ownerOfRoot[root] = static_cast<int>(r);
            m_curveOfRoot[root] = all[static_cast<std::size_t>(i) + 1];
        }
}

std::int64_t CellLayout::firstRow(std::size_t b) const {
    return static_cast<std::int64_t>((m_firstCurve + b) * m_cellsInBlock);
}

std::optional<GlobalCell> CellLayout::wrap(GlobalCell c) const {
    auto const& periodic = m_forest->periodic();
    for (int a = 0; a < 3; ++a) {
        if (c[a] >= 0 && c[a] < m_global[a])
            continue;
        if (!periodic[a])
            return std::nullopt;
        c[a] = ((c[a] % m_global[a]) + m_global[a]) % m_global[a];
    }
    return c;
}

std::optional<CellOwner> CellLayout::owner(GlobalCell const& c) const {
    auto const w = wrap(c);
    if (!w)
        return std::nullopt;
    domain::LatticeCell root{};
    std::array<int, 3> local{};
    for (int a = 0; a < 3; ++a) {
        root[a] = (*w)[a] / m_n[a];
        local[a] = static_cast<int>((*w)[a] - root[a] * m_n[a]);
    }
    auto const rootIndex = static_cast<std::size_t>(m_forest->geometry().rootIndex(root));
    CellOwner o;
    o.rank = m_ownerOfRoot[rootIndex];
    o.interior = static_cast<std::size_t>(local[0]) +
                 static_cast<std::size_t>(m_n[0]) *
                     (static_cast<std::size_t>(local[1]) +
                      static_cast<std::size_t>(m_n[1]) * static_cast<std::size_t>(local[2]));
    o.pad = padIndex(local[0], local[1], local[2]);
    auto const curve = m_curveOfRoot[rootIndex];
    o.row =
        curve * static_cast<std::int64_t>(m_cellsInBlock) + static_cast<std::int64_t>(o.interior);
    if (o.rank == m_forest->rank())
        o.localBlock = static_cast<int>(static_cast<std::size_t>(curve) - m_firstCurve);
    return o;
}

std::pair<std::size_t, std::size_t> CellLayout::localOfRow(std::int64_t row) const {
    auto const r = static_cast<std::size_t>(row - m_rowBegin);
    return {r / m_cellsInBlock, r % m_cellsInBlock};
}

core::Vec3 CellLayout::centre(GlobalCell const& c) const {
    core::Vec3 p;
    for (int a = 0; a < 3; ++a)
        p[a] = m_forest->domain().min[a] + (static_cast<double>(c[a]) + 0.5) * m_h[a];
    return p;
}

core::Vec3 CellLayout::cellCoordinate(core::Vec3 const& p) const {
    return ((p - m_forest->domain().min).array() / m_h.array() - 0.5).matrix();
}

} // namespace regolith::gravity
