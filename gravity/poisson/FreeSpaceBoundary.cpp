#include "gravity/poisson/FreeSpaceBoundary.hpp"

#include <mpi.h>

#include <cmath>
#include <numeric>

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
    std::vector<double> mine;
    auto const& n = layout.cellsPerBlock();
    double const volume = layout.cellVolume();
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    double const m = density.at(b, i, j, k) * volume;
                    if (m == 0.0)
                        continue;
                    auto const& o = layout.origin(b);
                    core::Vec3 const x = layout.centre({o[0] + i, o[1] + j, o[2] + k});
                    mine.insert(mine.end(), {x[0], x[1], x[2], m});
                }
    int const count = static_cast<int>(mine.size());
    std::vector<int> counts = comm.allGather(count);
    std::vector<int> displs(counts.size(), 0);
    std::exclusive_scan(counts.begin(), counts.end(), displs.begin(), 0);
    m_cells.resize(static_cast<std::size_t>(displs.back() + counts.back()));
    core::Comm::check(MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, m_cells.data(), counts.data(),
                                     displs.data(), MPI_DOUBLE, comm.raw()),
                      "MPI_Allgatherv");
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
