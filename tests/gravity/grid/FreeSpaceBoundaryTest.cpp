// The free-space boundary values: the tree over the occupied cells against the exact sum
// over the same cells, at every ghost cell beyond the domain faces, for mass spread through
// the domain, mass close to a face and corner, and a mass distribution far off-centre (where
// a single expansion about the centre of mass is poor); with Newton's kernel and with the
// 7-point lattice's near the mass.
#include "gravity/poisson/FreeSpaceBoundary.hpp"

#include "gravity/field/CellField.hpp"
#include "tests/gravity/grid/GridTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace regolith;
using namespace regolith::gravity;

namespace {

/// Every ghost cell one layer beyond a face of the global grid (faces only, no edges).
std::vector<GlobalCell> faceGhosts(CellLayout const& layout) {
    auto const& N = layout.globalCells();
    std::vector<GlobalCell> out;
    for (std::size_t a = 0; a < 3; ++a) {
        std::size_t const b = (a + 1) % 3;
        std::size_t const c = (a + 2) % 3;
        for (std::int64_t side : {std::int64_t{-1}, N[a]})
            for (std::int64_t v = 0; v < N[c]; ++v)
                for (std::int64_t u = 0; u < N[b]; ++u) {
                    GlobalCell g{};
                    g[a] = side;
                    g[b] = u;
                    g[c] = v;
                    out.push_back(g);
                }
    }
    return out;
}

/// Fills density component 0 from f(centre) on this rank's cells.
template <class F>
void fill(CellField& rho, F&& f) {
    auto const& layout = rho.layout();
    auto const& n = layout.cellsPerBlock();
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b) {
        auto const& o = layout.origin(b);
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i)
                    rho.at(b, i, j, k) = f(layout.centre({o[0] + i, o[1] + j, o[2] + k}));
    }
}

/// Largest |φ_tree - φ_exact| / max |φ_exact| over the face ghosts; exact: the sum over the
/// occupied cells with Newton's kernel, or with the lattice's within its radius.
double boundaryError(core::Comm const& world, CellField const& rho, BoundaryKernel kernel) {
    FreeSpaceBoundary boundary(kernel);
    boundary.update(world, rho, 1.0);
    EXPECT_TRUE(boundary.usesTree());
    auto const& layout = rho.layout();
    std::vector<GlobalCell> ghosts = faceGhosts(layout);
    std::vector<core::Vec3> points;
    for (std::size_t i : FreeSpaceBoundary::coherentOrder(ghosts))
        points.push_back(layout.centre(ghosts[i]));
    EXPECT_EQ(points.size(), ghosts.size()); // a permutation
    std::vector<double> phi(points.size());
    boundary.evaluate(points, phi);

    std::vector<double> mine;
    forEachOccupiedCell(rho, [&](core::Vec3 const& x, double m) {
        mine.insert(mine.end(), {x[0], x[1], x[2], m});
    });
    std::vector<double> const cells = world.allGatherVarying<double>(mine);
    int const R = FreeSpaceBoundary::kLatticeRadius;
    LatticeGreensFunction const lattice(layout.spacing(), R);
    double worst = 0.0;
    double largest = 0.0;
    for (std::size_t p = 0; p < points.size(); ++p) {
        double exact = 0.0;
        for (std::size_t c = 0; c < cells.size(); c += 4) {
            core::Vec3 const d = points[p] - core::Vec3(cells[c], cells[c + 1], cells[c + 2]);
            core::Vec3 const n = d.cwiseQuotient(layout.spacing());
            std::array<std::int64_t, 3> const offset{std::llround(n[0]), std::llround(n[1]),
                                                     std::llround(n[2])};
            bool const near =
                std::abs(offset[0]) <= R && std::abs(offset[1]) <= R && std::abs(offset[2]) <= R;
            exact -=
                cells[c + 3] * (kernel == BoundaryKernel::Lattice && near ? lattice.kernel(offset)
                                                                          : 1.0 / d.norm());
        }
        worst = std::max(worst, std::abs(phi[p] - exact));
        largest = std::max(largest, std::abs(exact));
    }
    return worst / largest;
}

TEST(FreeSpaceBoundary, TreeMatchesTheExactSumOverOccupiedCells) {
    core::Comm world;
    auto const spec = test::cubeSpec(world, 2, 32, {false, false, false}, 2.0);
    domain::BlockForest forest(world, spec);
    CellLayout layout(world, forest, spec.cellsPerBlock, 1);
    CellField rho(layout);

    // Two smooth balls, one off-centre (as grid_bench).
    auto const ball = [](core::Vec3 const& x, core::Vec3 const& c, double R) {
        double const s = (x - c).squaredNorm() / (R * R);
        return s < 1.0 ? (1.0 - s) * (1.0 - s) : 0.0;
    };
    fill(rho, [&](core::Vec3 const& x) {
        return ball(x, {0.1, 0.0, -0.1}, 0.5) + 3.0 * ball(x, {0.9, 0.7, 0.6}, 0.2);
    });
    for (auto const kernel : {BoundaryKernel::Newton, BoundaryKernel::Lattice})
        EXPECT_LT(boundaryError(world, rho, kernel), 1e-4) << "two balls";

    // Mass touching a face and a corner cell, and scattered cells of random mass.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    fill(rho, [&](core::Vec3 const& x) {
        double v = u(rng) < 0.02 ? u(rng) : 0.0;
        if (x[0] > 1.85 && std::abs(x[1]) < 0.5 && std::abs(x[2]) < 0.5)
            v += 5.0; // a slab on the +x face
        if (x[0] < -1.85 && x[1] < -1.85 && x[2] < -1.85)
            v += 20.0; // the corner cell
        return v;
    });
    for (auto const kernel : {BoundaryKernel::Newton, BoundaryKernel::Lattice})
        EXPECT_LT(boundaryError(world, rho, kernel), 1e-4)
            << "face, corner and scattered cells, kernel " << static_cast<int>(kernel);
}

TEST(FreeSpaceBoundary, CoherentOrderIsAPermutationThatKeepsNeighboursTogether) {
    std::vector<GlobalCell> cells;
    for (std::int64_t k = 0; k < 16; ++k)
        for (std::int64_t j = 0; j < 16; ++j)
            cells.push_back({-1, j, k});
    auto const order = FreeSpaceBoundary::coherentOrder(cells);
    std::vector<int> seen(cells.size(), 0);
    for (std::size_t i : order)
        ++seen[i];
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
    // Morton order over a complete 16 x 16 face: every aligned run of 4 is a 2 x 2 square.
    for (std::size_t r = 0; r + 4 <= order.size(); r += 4) {
        std::int64_t span = 0;
        for (std::size_t q = 1; q < 4; ++q)
            for (std::size_t a = 1; a < 3; ++a)
                span = std::max(span, std::abs(cells[order[r + q]][a] - cells[order[r]][a]));
        EXPECT_LE(span, 1) << "run " << r / 4;
    }
}

} // namespace
