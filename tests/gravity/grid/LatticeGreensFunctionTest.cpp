// The 7-point Laplacian's lattice Green's function: Watson's value at the origin, the
// discrete Poisson equation it solves (on cubic and anisotropic lattices), and Newton's 1/r
// far out, which the table's corrections approach as h² / r³.
#include "gravity/poisson/LatticeGreensFunction.hpp"

#include "core/Error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace regolith;
using namespace regolith::gravity;

namespace {

using Offset = std::array<std::int64_t, 3>;

/// -Δ_h K at offset n (every neighbour within the table).
double negativeLaplacian(LatticeGreensFunction const& g, Offset const& n) {
    double sum = 0.0;
    for (std::size_t a = 0; a < 3; ++a) {
        double const h = g.spacing()[static_cast<Eigen::Index>(a)];
        Offset up = n, down = n;
        ++up[a];
        --down[a];
        sum += (2.0 * g.kernel(n) - g.kernel(up) - g.kernel(down)) / (h * h);
    }
    return sum;
}

} // namespace

TEST(LatticeGreensFunction, WatsonsIntegralAtTheOrigin) {
    LatticeGreensFunction const g({1.0, 1.0, 1.0}, 4);
    // Watson (1939): the simple cubic lattice's Green's function at 0 is 0.2527310098586632...
    EXPECT_NEAR(g.kernel({0, 0, 0}) / (4.0 * std::numbers::pi), 0.2527310098586632, 1e-13);
    // Lengths scale it as 1 / h.
    LatticeGreensFunction const half({0.5, 0.5, 0.5}, 1);
    EXPECT_NEAR(half.kernel({0, 0, 0}), 2.0 * g.kernel({0, 0, 0}), 1e-12);
    EXPECT_NEAR(half.kernel({1, 1, 0}), 2.0 * g.kernel({1, -1, 0}), 1e-12);
}

TEST(LatticeGreensFunction, SolvesTheDiscretePoissonEquation) {
    for (core::Vec3 const& h : {core::Vec3(1.0, 1.0, 1.0), core::Vec3(0.3, 0.45, 0.9)}) {
        LatticeGreensFunction const g(h, 8);
        double const fourPiOverV = 4.0 * std::numbers::pi / h.prod();
        EXPECT_NEAR(negativeLaplacian(g, {0, 0, 0}) / fourPiOverV, 1.0, 1e-12) << h.transpose();
        for (Offset const n : {Offset{1, 0, 0}, Offset{0, 2, 1}, Offset{3, -4, 5}, Offset{7, 7, 7},
                               Offset{-2, 0, 7}})
            EXPECT_NEAR(negativeLaplacian(g, n) / fourPiOverV, 0.0, 1e-12)
                << h.transpose() << " at " << n[0] << " " << n[1] << " " << n[2];
    }
}

TEST(LatticeGreensFunction, ApproachesNewtonAsTheInverseCube) {
    LatticeGreensFunction const g({1.0, 1.0, 1.0}, 16);
    // Along an axis the correction is 1 / (4 r³) to leading order (the lattice's anisotropy,
    // (5 Σ x_a⁴ / r⁴ - 3) / (8 r³)), so r³ times it tends to 1/4.
    for (std::int64_t r : {8, 12, 16}) {
        double const d = static_cast<double>(r);
        EXPECT_NEAR(g.correction({r, 0, 0}) * d * d * d, 0.25, 1.0 / (d * d))
            << r; // next: ~0.75 / r²
        EXPECT_NEAR(g.kernel({0, r, 0}), 1.0 / d, 0.3 / (d * d * d)) << r;
    }
    // Along a body diagonal the leading term vanishes ((5/3 - 3) / 8 r³ = -1/6 r³).
    double const d = std::sqrt(3.0) * 8.0;
    EXPECT_NEAR(g.correction({8, 8, 8}) * d * d * d, -1.0 / 6.0, 0.6 / (d * d));
    EXPECT_THROW(LatticeGreensFunction({1.0, 0.0, 1.0}, 2), core::Error);
    EXPECT_THROW(LatticeGreensFunction({1.0, 1.0, 1.0}, LatticeGreensFunction::kMaxRadius + 1),
                 core::Error);
}
