// P3M in the coupled path (SelfGravityForces with gravity.self = "p3m", masters in
// particles::LocalParticles): where the bare mesh fails (two grains closer than 2 h, here
// across a block face and, on 2 and 4 ranks, across ranks; and across a periodic face) P3M
// gives the Newtonian pair force; on a packed agglomerate it agrees with the direct sum
// within the mesh's residual anisotropy. 1, 2, 4 ranks, G = 1, h = 1/2 (32³ cells).
#include "gravity/samples/SyntheticBodies.hpp"
#include "tests/coupling/CouplingTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

using namespace regolith;
using coupling::test::GlobalGrains;

namespace {

domain::ForestSpec forestSpec(bool periodic) {
    domain::ForestSpec spec;
    spec.domain = core::AABB{core::Vec3::Constant(-8.0), core::Vec3::Constant(8.0)};
    spec.rootBlocks = {2, 2, 2};
    spec.periodic = {periodic, periodic, periodic};
    spec.cellsPerBlock = {16, 16, 16}; // h = 0.5
    return spec;
}

coupling::SelfGravityConfig config(std::string const& method, domain::ForestSpec const& spec) {
    coupling::SelfGravityConfig c;
    c.method = method;
    c.G = 1.0;
    c.cellsPerBlock = spec.cellsPerBlock;
    c.gradientOrder = 4;
    return c;
}

/// |a - a_exact| / |a_exact| of grain 0 of a pair, a_exact = G m1 / r² towards grain 1 (the
/// minimum image on a periodic domain).
double pairError(domain::ForestSpec const& spec, GlobalGrains const& pair,
                 std::string const& method) {
    domain::BlockForest const forest(coupling::test::world(), spec);
    auto const field = coupling::test::selfGravity(forest, pair, config(method, spec));
    core::Vec3 d = pair.position[1] - pair.position[0];
    for (int a = 0; a < 3; ++a)
        if (spec.periodic[static_cast<std::size_t>(a)])
            d[a] -= 16.0 * std::round(d[a] / 16.0);
    core::Vec3 const exact = pair.mass[1] / d.squaredNorm() * d.normalized();
    return (field.acceleration[0] - exact).norm() / exact.norm();
}

/// Two grains one cell apart across the block face x = 0 (on 2 and 4 ranks also a rank
/// boundary), off the grid axes. Measured: mesh 58 % too weak, P3M 2.2 % off (TSC, 4th-order
/// gradient; what remains is how the mesh force depends on where the grains sit in their
/// cells, up to ~5 % at 1 h in PairForceTest).
TEST(P3mCoupling, TwoCloseGrainsMeshFailsP3mRepairs) {
    core::Vec3 const dir = core::Vec3{1.0, 0.37, -0.21}.normalized();
    core::Vec3 const centre{0.0, 0.13, -0.07};
    double const h = 0.5;
    GlobalGrains pair;
    pair.position = {centre - 0.5 * h * dir, centre + 0.5 * h * dir};
    pair.mass = {1.0, 2.0};
    pair.radius = {0.1, 0.1};
    auto const spec = forestSpec(false);
    double const mesh = pairError(spec, pair, "pm");
    double const p3m = pairError(spec, pair, "p3m");
    if (coupling::test::world().rank() == 0)
        std::printf("pair at 1 h: mesh error %.3f, P3M error %.4f\n", mesh, p3m);
    EXPECT_GT(mesh, 0.3);
    EXPECT_LT(p3m, 0.06);
}

/// The same through a periodic face: the pair is found through the halo's periodic image
/// (on one rank an image of the rank's own grain).
TEST(P3mCoupling, ClosePairAcrossAPeriodicFace) {
    GlobalGrains pair;
    pair.position = {{-7.85, 0.21, 0.33}, {7.8, 0.02, 0.41}}; // 0.35 apart through x = ±8
    pair.mass = {1.0, 1.5};
    pair.radius = {0.1, 0.1};
    auto const spec = forestSpec(true);
    double const mesh = pairError(spec, pair, "pm");
    double const p3m = pairError(spec, pair, "p3m");
    if (coupling::test::world().rank() == 0)
        std::printf("periodic pair at 0.8 h: mesh error %.3f, P3M error %.4f\n", mesh, p3m);
    EXPECT_GT(mesh, 0.3);
    EXPECT_LT(p3m, 0.06);
}

/// The potential energy of a pair is -G m1 m2 / r wherever the grains sit in their cells, in
/// free space: apart (12 h: the mesh's pair potential, with each grain's self-energy measured
/// at its position and removed) and within the cut-off (0.7 h, 2.5 h: exact by P3M's pair
/// term). Before the self-energy was measured per grain the 12 h pair's energy ranged over
/// -2.4 to -3.4 against -0.667 (m1 m2 = 4, r = 6). Bound 0.1 % (measured 1.5e-4 at 12 h,
/// the mesh potential's own error there; 1e-6 within the cut-off). On a periodic domain the
/// energy also holds the images (Ewald): the change between two close separations is the
/// Newtonian one, and the energy does not jump as the pair crosses the cut-off (by 35 % of the
/// pair's energy when the table's image part was removed inside it only).
TEST(P3mCoupling, PairEnergyIsNewtonianWhereverTheGrainsSit) {
    double const h = 0.5;
    core::Vec3 const dir = core::Vec3{1.0, 0.3, -0.4}.normalized();
    for (bool const periodic : {false, true}) {
        auto const spec = forestSpec(periodic);
        domain::BlockForest const forest(coupling::test::world(), spec);
        auto energy = [&](core::Vec3 const& start, double sep) {
            GlobalGrains pair;
            pair.position = {start - 0.5 * sep * dir, start + 0.5 * sep * dir};
            pair.mass = {1.0, 4.0};
            pair.radius = {0.0, 0.0};
            double const e =
                coupling::test::selfGravity(forest, pair, config("p3m", spec)).potentialEnergy;
            if (coupling::test::world().rank() == 0)
                std::printf("%s pair at %.3f h from %g %g %g: energy %.5f, Newtonian %.5f\n",
                            periodic ? "periodic" : "free-space", sep / h, start.x(), start.y(),
                            start.z(), e, -4.0 / sep);
            return e;
        };
        double worst = 0.0;
        for (core::Vec3 const& start : {core::Vec3{0.0, 0.0, 0.0}, core::Vec3{0.25, 0.25, 0.25},
                                        core::Vec3{0.1, -0.2, 0.05}}) {
            if (!periodic) {
                for (double const sep : {0.7 * h, 2.5 * h, 12.0 * h})
                    worst = std::max(worst, std::abs(energy(start, sep) / (-4.0 / sep) - 1.0));
            } else {
                double const change = energy(start, 2.5 * h) - energy(start, 0.7 * h);
                double const newtonian = -4.0 / (2.5 * h) + 4.0 / (0.7 * h);
                worst = std::max(worst, std::abs(change / newtonian - 1.0));
            }
        }
        EXPECT_LT(worst, 1e-3) << (periodic ? "periodic" : "free space");
        if (periodic) { // across the cut-off of 4 h: the jump was 2.84 G m1 m2 / L = 0.71
            double const inside = energy(core::Vec3::Zero(), 3.99 * h);
            double const outside = energy(core::Vec3::Zero(), 4.01 * h);
            EXPECT_NEAR(inside, outside, 0.02 * 4.0 / (4.0 * h)); // 2 % of the pair's energy
        }
    }
}

/// A packed agglomerate of 500 grains (radii 0.1-0.2, about 7 cells across, so most of each
/// grain's pull comes from within the 4-cell cut-off): per-grain relative force error against
/// the direct sum. Tolerances (measured 0.36 % and 0.95 % on 1, 2, 4 ranks): median 1 %, 99th
/// percentile 3 % (the mesh force's dependence on the grains' positions in their cells, and its
/// ~0.3 % error beyond the cut-off); the bare mesh (10.6 %), asserted at least 5 times worse in
/// the median. The potential energy within 0.01 % of the direct sum's (measured 0.001 %;
/// 0.23 % before each grain's self-energy was measured where it sits).
TEST(P3mCoupling, AgreesWithTheDirectSumOnAnAgglomerate) {
    auto const body = gravity::samples::packedAgglomerate(500, 0.1, 0.2, 1.0, 0.3,
                                                          core::Vec3{0.31, -0.22, 0.13}, 5);
    GlobalGrains grains;
    for (std::size_t k = 0; k < body.size(); ++k) {
        grains.position.emplace_back(body.x[k], body.y[k], body.z[k]);
        grains.mass.push_back(body.m[k]);
        grains.radius.push_back(0.0); // points for the mesh, as P3M deposits them
    }
    auto const spec = forestSpec(false);
    domain::BlockForest const forest(coupling::test::world(), spec);
    auto errors = [&](std::string const& method, double& energyError) {
        auto const direct = coupling::test::selfGravity(forest, grains, config("direct", spec));
        auto const approx = coupling::test::selfGravity(forest, grains, config(method, spec));
        std::vector<double> e;
        for (std::size_t k = 0; k < grains.position.size(); ++k)
            e.push_back((approx.acceleration[k] - direct.acceleration[k]).norm() /
                        direct.acceleration[k].norm());
        std::sort(e.begin(), e.end());
        energyError = std::abs(approx.potentialEnergy / direct.potentialEnergy - 1.0);
        return std::pair{e[e.size() / 2], e[e.size() * 99 / 100]};
    };
    double meshEnergy = 0.0, p3mEnergy = 0.0;
    auto const mesh = errors("pm", meshEnergy);
    auto const p3m = errors("p3m", p3mEnergy);
    if (coupling::test::world().rank() == 0)
        std::printf("agglomerate, 500 grains: mesh median %.4f p99 %.4f energy %.4f; P3M median "
                    "%.5f p99 %.5f energy %.5f\n",
                    mesh.first, mesh.second, meshEnergy, p3m.first, p3m.second, p3mEnergy);
    EXPECT_LT(p3m.first, 0.01);
    EXPECT_LT(p3m.second, 0.03);
    EXPECT_LT(5.0 * p3m.first, mesh.first);
    EXPECT_LT(p3mEnergy, 1e-4);
}

/// The second paper's node methods through the coupled path, on the same agglomerate with its
/// grains' radii: nodes 2.5 largest diameters apart (the paper's spacing), fields interpolated
/// from the nodes. Measured median 17.7 % (both; 6.6 % on 3,866 grains in docs/results.md:
/// fewer grains per node spacing, larger error); bound 30 %: the
/// paper's methods trade accuracy for speed, so the bound only guards against regressions and
/// a wrong coupling (grains in the wrong frame or order would give errors of order 1).
TEST(NodeMethodsCoupling, AgreeWithTheDirectSumOnAnAgglomerate) {
    auto const body = gravity::samples::packedAgglomerate(500, 0.1, 0.2, 1.0, 0.3,
                                                          core::Vec3{0.31, -0.22, 0.13}, 5);
    GlobalGrains grains;
    for (std::size_t k = 0; k < body.size(); ++k) {
        grains.position.emplace_back(body.x[k], body.y[k], body.z[k]);
        grains.mass.push_back(body.m[k]);
        grains.radius.push_back(body.r[k]);
    }
    auto const spec = forestSpec(false);
    domain::BlockForest const forest(coupling::test::world(), spec);
    auto const direct = coupling::test::selfGravity(forest, grains, config("direct", spec));
    for (std::string const method : {"occupied-cells", "tree-nodes"}) {
        auto c = config(method, spec);
        c.gridSpacing = 2.5 * 0.4;
        c.neighbourhood = c.gridSpacing;
        auto const approx = coupling::test::selfGravity(forest, grains, c);
        std::vector<double> e;
        for (std::size_t k = 0; k < grains.position.size(); ++k)
            e.push_back((approx.acceleration[k] - direct.acceleration[k]).norm() /
                        direct.acceleration[k].norm());
        std::sort(e.begin(), e.end());
        double const median = e[e.size() / 2];
        double const energy = std::abs(approx.potentialEnergy / direct.potentialEnergy - 1.0);
        if (coupling::test::world().rank() == 0)
            std::printf("%s: median %.4f p99 %.4f energy %.4f\n", method.c_str(), median,
                        e[e.size() * 99 / 100], energy);
        EXPECT_LT(median, 0.3);
    }
}

} // namespace
