#pragma once
/// A cell field on this rank's blocks: `components` doubles per cell, interior plus ghost
/// layers, one contiguous array per block and component (component-major), laid out as
/// CellLayout::padIndex says. Plain storage: ghost values are whatever the last ghost
/// exchange (or the caller) put there.
#include "gravity/field/CellLayout.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace regolith::gravity {

class CellField {
public:
    /// Zero-initialised. Pre: `layout` outlives this object; components >= 1.
    explicit CellField(CellLayout const& layout, int components = 1)
        : m_layout(&layout)
        , m_components(components)
        , m_data(layout.localBlockCount() * static_cast<std::size_t>(components) *
                     layout.paddedCellsInBlock(),
                 0.0) {}

    [[nodiscard]] CellLayout const& layout() const { return *m_layout; }
    [[nodiscard]] int components() const { return m_components; }

    /// The padded array of local block b, component c.
    [[nodiscard]] std::span<double> block(std::size_t b, int c = 0) {
        return {m_data.data() + offset(b, c), m_layout->paddedCellsInBlock()};
    }
    [[nodiscard]] std::span<double const> block(std::size_t b, int c = 0) const {
        return {m_data.data() + offset(b, c), m_layout->paddedCellsInBlock()};
    }
    /// Cell (i, j, k) of block b, each index in [-ghost, n + ghost).
    [[nodiscard]] double& at(std::size_t b, int i, int j, int k, int c = 0) {
        return m_data[offset(b, c) + m_layout->padIndex(i, j, k)];
    }
    [[nodiscard]] double at(std::size_t b, int i, int j, int k, int c = 0) const {
        return m_data[offset(b, c) + m_layout->padIndex(i, j, k)];
    }
    void fill(double v) { std::fill(m_data.begin(), m_data.end(), v); }
    /// Sum of the interior cells of component c over this rank's blocks (no ghosts). Local.
    [[nodiscard]] double localInteriorSum(int c = 0) const;

private:
    [[nodiscard]] std::size_t offset(std::size_t b, int c) const {
        return (b * static_cast<std::size_t>(m_components) + static_cast<std::size_t>(c)) *
               m_layout->paddedCellsInBlock();
    }

    CellLayout const* m_layout;
    int m_components;
    std::vector<double> m_data;
};

/// Calls f(centre, mass) for every interior cell of the local blocks whose mass (density x
/// cell volume) is not zero: the occupied cells the free-space boundary sums over. Not
/// collective.
template <class F>
void forEachOccupiedCell(CellField const& density, F&& f) {
    CellLayout const& layout = density.layout();
    auto const& n = layout.cellsPerBlock();
    double const volume = layout.cellVolume();
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b) {
        auto const& o = layout.origin(b);
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    double const m = density.at(b, i, j, k) * volume;
                    if (m != 0.0)
                        f(layout.centre({o[0] + i, o[1] + j, o[2] + k}), m);
                }
    }
}

} // namespace regolith::gravity
