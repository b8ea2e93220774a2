#include "gravity/poisson/FreeSpaceBoundary.hpp"

#include <cmath>

namespace regolith::gravity {

void FreeSpaceBoundary::update(core::Comm const& comm, CellField const& density, double G) {
    m_G = G;
    m_moments = massMoments(comm, density);
    auto const& layout = density.layout();
    auto const& N = layout.globalCells();
    double const boundaryCells = 2.0 * static_cast<double>(N[0] * N[1] + N[1] * N[2] + N[0] * N[2]);
    m_direct = m_moments.occupiedCells * boundaryCells <= kDirectWork;
    m_cells.clear();
    if (!m_direct)
        return;
    // Every rank's occupied cells as (x, y, z, m), on every rank.
    std::vector<double> mine;
    forEachOccupiedCell(density, [&](core::Vec3 const& x, double m) {
        mine.insert(mine.end(), {x[0], x[1], x[2], m});
    });
    m_cells = comm.allGatherVarying<double>(mine);
}

double FreeSpaceBoundary::at(core::Vec3 const& x) const {
    if (!m_direct)
        return m_moments.mass > 0.0 ? multipolePotential(m_moments, m_G, x) : 0.0;
    double phi = 0.0;
    for (std::size_t c = 0; c < m_cells.size(); c += 4) {
        double const dx = x[0] - m_cells[c];
        double const dy = x[1] - m_cells[c + 1];
        double const dz = x[2] - m_cells[c + 2];
        phi -= m_cells[c + 3] / std::sqrt(dx * dx + dy * dy + dz * dz);
    }
    return m_G * phi;
}

} // namespace regolith::gravity
