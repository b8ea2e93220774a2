#include "gravity/MeshPotentialTable.hpp"

#include "core/Error.hpp"
#include "gravity/transfer/AssignmentKernels.hpp"

#include <array>
#include <cmath>

namespace regolith::gravity {

std::vector<std::array<int, 3>> axisPermutations(core::Vec3 const& spacing) {
    if ((spacing.maxCoeff() - spacing.minCoeff()) <= 1e-12 * spacing.maxCoeff())
        return {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    return {{0, 1, 2}};
}

MeshPotentialTable::MeshPotentialTable(core::Comm const& comm, GridGravity& gravity, double radius)
    : m_layout(&gravity.layout())
    , m_assignment(gravity.assignment())
    , m_G(gravity.G())
    , m_radius(radius) {
    core::Vec3 const centre = m_layout->forest().domain().center();
    measureCellPotential(comm, gravity, centre);
    // On a periodic domain the table also holds the images' and the background's potential:
    // its regular part at m_radius (P3M's cut-off) is kept apart, so that P3M's corrections
    // vanish there and each grain keeps its share with its own images, as the Ewald sum has
    // it. Averaged over the 26 directions of the cube's faces, edges and corners. In free
    // space the mesh is taken as exact from m_radius on (its ~0.4 % there would only shift
    // every close pair's energy).
    double sum = 0.0;
    int count = 0;
    for (int z = -1; z <= 1 && gravity.periodic(); ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x)
                if (x != 0 || y != 0 || z != 0) {
                    core::Vec3 const d = core::Vec3(x, y, z).normalized();
                    sum += meshPotential(centre, centre + m_radius * d) + m_G / m_radius;
                    ++count;
                }
    m_regular = count > 0 ? sum / count : 0.0;
    // The grains' first solve must not start from the unit source's potential (with a
    // periodic domain its residual exceeded PETSc's divergence bound before the first step).
    gravity.resetInitialGuess();
}

void MeshPotentialTable::measureCellPotential(core::Comm const& comm, GridGravity& gravity,
                                              core::Vec3 const& source) {
    CellLayout const& layout = gravity.layout();
    // Offsets a pair within m_radius reaches: the cells between the two grains plus each
    // kernel's width (TSC: 3 cells, so the weights' offsets differ by up to 2 more).
    m_reach = static_cast<std::int64_t>(std::ceil(m_radius / layout.spacing().minCoeff())) + 3;
    auto const side = static_cast<std::size_t>(2 * m_reach + 1);
    core::Vec3 const u = layout.cellCoordinate(source);
    GlobalCell const cell{std::llround(u[0]), std::llround(u[1]), std::llround(u[2])};
    CellField& density = gravity.density();
    density.fill(0.0);
    auto const at = layout.owner(cell);
    if (!at)
        throw core::Error("MeshPotentialTable: the calibration cell lies outside the domain");
    if (at->localBlock >= 0) // unit G m in one cell
        density.block(static_cast<std::size_t>(at->localBlock))[at->pad] =
            1.0 / (m_G * layout.cellVolume());
    gravity.solveFromDensity();
    // Each offset read where its cell lives (value, 1), summed over the ranks.
    std::vector<double> raw(2 * side * side * side, 0.0);
    CellField const& phi = gravity.potential();
    std::size_t v = 0;
    for (std::int64_t k = -m_reach; k <= m_reach; ++k)
        for (std::int64_t j = -m_reach; j <= m_reach; ++j)
            for (std::int64_t i = -m_reach; i <= m_reach; ++i, ++v) {
                auto const o = layout.owner({cell[0] + i, cell[1] + j, cell[2] + k});
                if (!o || o->localBlock < 0)
                    continue;
                raw[2 * v] = phi.block(static_cast<std::size_t>(o->localBlock))[o->pad];
                raw[2 * v + 1] = 1.0;
            }
    comm.allReduceInPlace(std::span<double>(raw), core::ReduceOp::Sum);
    // Averaged over the reflections (and the axis permutations of cubic cells) of the
    // offsets the domain holds: the free-space boundary breaks the symmetry only slightly.
    core::Vec3 const& h = layout.spacing();
    auto const perms = axisPermutations(h);
    auto index = [&](std::array<std::int64_t, 3> const& e) {
        auto const s = static_cast<std::int64_t>(side);
        return static_cast<std::size_t>((e[0] + m_reach) +
                                        s * ((e[1] + m_reach) + s * (e[2] + m_reach)));
    };
    m_cell.assign(side * side * side, 0.0);
    for (std::int64_t k = -m_reach; k <= m_reach; ++k)
        for (std::int64_t j = -m_reach; j <= m_reach; ++j)
            for (std::int64_t i = -m_reach; i <= m_reach; ++i) {
                std::array<std::int64_t, 3> const e{i, j, k};
                double sum = 0.0, count = 0.0;
                for (auto const& p : perms)
                    for (int signs = 0; signs < 8; ++signs) {
                        std::array<std::int64_t, 3> w{};
                        for (std::size_t a = 0; a < 3; ++a)
                            w[a] = (((signs >> a) & 1) != 0 ? -1 : 1) *
                                   e[static_cast<std::size_t>(p[a])];
                        sum += raw[2 * index(w)];
                        count += raw[2 * index(w) + 1];
                    }
                double const r =
                    core::Vec3(static_cast<double>(i) * h.x(), static_cast<double>(j) * h.y(),
                               static_cast<double>(k) * h.z())
                        .norm();
                m_cell[index(e)] = count > 0.0 ? sum / count : -1.0 / r;
            }
}

double MeshPotentialTable::cellPotential(std::int64_t i, std::int64_t j, std::int64_t k) const {
    auto const s = 2 * m_reach + 1;
    return m_cell[static_cast<std::size_t>((i + m_reach) +
                                           s * ((j + m_reach) + s * (k + m_reach)))];
}

double MeshPotentialTable::meshPotential(core::Vec3 const& xi, core::Vec3 const& xj) const {
    // Per axis, the two stencils' products summed by cell offset (cell of i minus cell of
    // j): the 3-D sum over both deposits factorises into these, 125 table reads for TSC.
    core::Vec3 const ui = m_layout->cellCoordinate(xi);
    core::Vec3 const uj = m_layout->cellCoordinate(xj);
    std::array<std::array<double, 5>, 3> weight{};
    std::array<std::int64_t, 3> lowest{};
    std::array<int, 3> width{};
    for (int a = 0; a < 3; ++a) {
        auto const ua = static_cast<std::size_t>(a);
        Stencil1D const si = stencil(m_assignment, ui[a]);
        Stencil1D const sj = stencil(m_assignment, uj[a]);
        lowest[ua] = si.first - sj.first - (sj.count - 1);
        width[ua] = si.count + sj.count - 1;
        for (int p = 0; p < si.count; ++p)
            for (int q = 0; q < sj.count; ++q)
                weight[ua][static_cast<std::size_t>(p - q + sj.count - 1)] +=
                    si.w[static_cast<std::size_t>(p)] * sj.w[static_cast<std::size_t>(q)];
    }
    for (std::size_t a = 0; a < 3; ++a)
        if (std::abs(lowest[a]) > m_reach || std::abs(lowest[a] + width[a] - 1) > m_reach)
            throw core::Error("MeshPotentialTable::meshPotential: the grains are beyond the table");
    double sum = 0.0;
    for (int z = 0; z < width[2]; ++z)
        for (int y = 0; y < width[1]; ++y) {
            double const wyz =
                weight[1][static_cast<std::size_t>(y)] * weight[2][static_cast<std::size_t>(z)];
            for (int x = 0; x < width[0]; ++x)
                sum += weight[0][static_cast<std::size_t>(x)] * wyz *
                       cellPotential(lowest[0] + x, lowest[1] + y, lowest[2] + z);
        }
    return m_G * sum;
}

double MeshPotentialTable::selfPotential(core::Vec3 const& x) const {
    return meshPotential(x, x) - m_regular;
}

double MeshPotentialTable::selfPotential(core::Vec3 const& x, double radius) const {
    // Beyond the table's reach (and already for a few cells: n^2 pairs of samples), the mesh
    // resolves the grain: a uniform ball's -6/5 G m / r, to O(h / r).
    if (2.0 * radius > m_radius)
        return -1.2 * m_G / radius - m_regular;
    if (!(radius > 0.5 * m_layout->spacing().minCoeff()))
        return selfPotential(x); // one sample, the centre (ballSamples): no list to build
    std::vector<core::Vec3> samples;
    ballSamples(radius, m_layout->spacing(), samples);
    double sum = 0.0;
    for (core::Vec3 const& p : samples)
        for (core::Vec3 const& q : samples)
            sum += meshPotential(x + p, x + q);
    auto const n = static_cast<double>(samples.size());
    return sum / (n * n) - m_regular;
}

} // namespace regolith::gravity
