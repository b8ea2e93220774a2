// Forces between grains from the mesh: two point masses far apart (>= 4 h) attract with
// equal and opposite forces that follow G m1 m2 / r^2 within 1 % (TSC with the fourth-order
// gradient), up to half the box (free-space boundary by direct sum: few occupied cells); closer
// than 2 h the mesh's softening makes the force far too weak (asserted large: that is where a
// short-range correction such as P3M is needed); a lone grain feels (almost) no self-force.
#include "gravity/GridGravity.hpp"
#include "gravity/GridShortRange.hpp"
#include "tests/gravity/grid/GridTestUtil.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <tuple>

using namespace regolith;
using namespace regolith::gravity;

namespace {

constexpr double kG = 1.0;

struct Pair {
    core::Vec3 forceA; ///< on grain A (mass mA)
    core::Vec3 forceB;
};

/// Grain A on rank 0, grain B on the last rank; both point masses (radius 0).
class PairForce : public ::testing::TestWithParam<std::tuple<Assignment, int, PoissonMethod>> {
protected:
    [[nodiscard]] std::string name() const {
        return std::string(toString(std::get<0>(GetParam()))) + " order " +
               std::to_string(std::get<1>(GetParam())) + " " + toString(std::get<2>(GetParam()));
    }

    void SetUp() override {
        spec = test::cubeSpec(world, 2, 32, {false, false, false}, 2.0); // h = 1/8
        forest = std::make_unique<domain::BlockForest>(world, spec);
        GridGravityOptions options;
        options.assignment = std::get<0>(GetParam());
        options.gradientOrder = std::get<1>(GetParam());
        options.poissonMethod = std::get<2>(GetParam());
        options.poisson.G = kG;
        gravity = std::make_unique<GridGravity>(world, *forest, spec.cellsPerBlock, options);
    }

    Pair forces(core::Vec3 const& a, core::Vec3 const& b, double mA, double mB) {
        std::vector<core::Vec3> pos;
        std::vector<double> mass;
        if (world.rank() == 0) {
            pos.push_back(a);
            mass.push_back(mA);
        }
        if (world.rank() == world.size() - 1) {
            pos.push_back(b);
            mass.push_back(mB);
        }
        Grains const grains{pos, {}, mass};
        gravity->update(grains);
        std::vector<core::Vec3> g(pos.size());
        gravity->accelerations(grains, g);
        std::array<double, 6> f{};
        if (world.rank() == 0)
            for (int c = 0; c < 3; ++c)
                f[static_cast<std::size_t>(c)] = mA * g.front()[c];
        if (world.rank() == world.size() - 1)
            for (int c = 0; c < 3; ++c)
                f[3 + static_cast<std::size_t>(c)] = mB * g.back()[c];
        world.allReduceInPlace(std::span<double>(f), core::ReduceOp::Sum);
        return {core::Vec3{f[0], f[1], f[2]}, core::Vec3{f[3], f[4], f[5]}};
    }

    core::Comm world;
    domain::ForestSpec spec;
    std::unique_ptr<domain::BlockForest> forest;
    std::unique_ptr<GridGravity> gravity;
};

/// 1 % needs TSC and the fourth-order gradient at 4 h (measured, 32^3 cells: TSC/4th order
/// 0.33 %, TSC/2nd order 2.0 %, CIC/4th order 3.2 %, CIC/2nd order 4.4 % at 4 h; all below
/// 1 % from 8 h on); the other kernels are held to what they reach.
TEST_P(PairForce, FarPairsFollowInverseSquareAndNewtonsThirdLaw) {
    double const h = gravity->layout().spacing()[0]; // 1/8; box width 4
    core::Vec3 const dir = core::Vec3{1.0, 0.37, -0.21}.normalized();
    core::Vec3 const centre{0.013, -0.021, 0.008}; // not on a cell centre or face
    for (double sep : {4 * h, 6 * h, 8 * h, 12 * h, 16 * h}) {
        core::Vec3 const a = centre - 0.5 * sep * dir;
        core::Vec3 const b = centre + 0.5 * sep * dir;
        double const mA = 1.0;
        double const mB = 2.5;
        Pair const p = forces(a, b, mA, mB);
        double const exact = kG * mA * mB / (sep * sep);
        double const along = p.forceA.dot(dir); // A is pulled towards B
        double const relError = std::abs(along - exact) / exact;
        double const imbalance = (p.forceA + p.forceB).norm() / exact;
        if (world.rank() == 0)
            std::printf("%s r = %.2f h: |F - F_exact| / F = %.4f, |F_A + F_B| / F = %.4f\n",
                        name().c_str(), sep / h, relError, imbalance);
        bool const best =
            std::get<0>(GetParam()) == Assignment::Tsc && std::get<1>(GetParam()) == 4;
        double const tolerance = best || sep >= 8 * h ? 0.01 : 0.05;
        EXPECT_LT(relError, tolerance) << name() << " separation " << sep / h << " h";
        EXPECT_LT(imbalance, 0.01) << "separation " << sep / h << " h";
    }
}

TEST_P(PairForce, ClosePairsAreBadlyResolved) {
    double const h = gravity->layout().spacing()[0];
    core::Vec3 const dir = core::Vec3{1.0, 0.37, -0.21}.normalized();
    for (double sep : {0.5 * h, 1.0 * h}) {
        Pair const p = forces(-0.5 * sep * dir, 0.5 * sep * dir, 1.0, 1.0);
        double const exact = kG / (sep * sep);
        double const relError = std::abs(p.forceA.dot(dir) - exact) / exact;
        if (world.rank() == 0)
            std::printf("%s r = %.2f h: |F - F_exact| / F = %.3f (mesh softening)\n",
                        name().c_str(), sep / h, relError);
        EXPECT_GT(relError, 0.3) << name() << " separation " << sep / h << " h";
    }
}

/// P3M: the mesh force plus the short-range correction for close pairs. What remains is the
/// mesh's anisotropy about its radial average, largest at 1-2 h; measured (full force
/// vector, random directions and offsets not used by the calibration, TSC with 4th-order
/// gradient) below 10 % where the bare mesh is 20-95 % off. Asserted for the pairs closer
/// than 2 h: the worst P3M error below 12 % and at least 5 times below the bare mesh's.
/// CIC with the 2nd-order gradient is more anisotropic: P3M leaves up to ~25 % there
/// (measured; not run, to keep the test time down).
TEST_P(PairForce, ShortRangeCorrectionRepairsClosePairs) {
    if (std::get<0>(GetParam()) != Assignment::Tsc)
        GTEST_SKIP() << "P3M is asserted for TSC with the 4th-order gradient";
    GridShortRange p3m(world, *gravity);
    double const h = gravity->layout().spacing()[0];
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double worstMesh = 0.0;
    double worstP3m = 0.0;
    for (double sep : {0.5 * h, 1.0 * h, 1.5 * h, 1.9 * h}) {
        double meshAtSep = 0.0;
        double p3mAtSep = 0.0;
        for (int trial = 0; trial < 3; ++trial) {
            core::Vec3 const dir = core::Vec3{u(rng), u(rng), u(rng)}.normalized();
            core::Vec3 const centre = h * core::Vec3{u(rng), u(rng), u(rng)};
            core::Vec3 const a = centre - 0.5 * sep * dir;
            core::Vec3 const b = centre + 0.5 * sep * dir;
            Pair const p = forces(a, b, 1.0, 2.0);
            double const exact = kG * 2.0 / (sep * sep);
            core::Vec3 const corrected = p.forceA + 1.0 * p3m.correction(b - a, 2.0);
            meshAtSep = std::max(meshAtSep, (p.forceA - exact * dir).norm() / exact);
            p3mAtSep = std::max(p3mAtSep, (corrected - exact * dir).norm() / exact);
        }
        if (world.rank() == 0)
            std::printf("%s r = %.1f h: worst mesh error %.3f, worst P3M error %.4f\n",
                        name().c_str(), sep / h, meshAtSep, p3mAtSep);
        worstMesh = std::max(worstMesh, meshAtSep);
        worstP3m = std::max(worstP3m, p3mAtSep);
    }
    EXPECT_GT(worstMesh, 0.3);
    EXPECT_LT(worstP3m, 0.12);
    EXPECT_LT(5.0 * worstP3m, worstMesh);
}

/// ½ Σ m φ includes each grain's mesh-softened self-energy (here ~10 times the pair's), which
/// depends on where a grain sits in its cell but not on where the pair is; moving the grains
/// by whole cells keeps it fixed, so the change between two separations is the pair's:
/// -G m1 m2 (1/r2 - 1/r1), within 2 % (measured 1.1 %: the mesh potential at 6 h).
TEST_P(PairForce, PotentialEnergyChangeOfAPair) {
    double const h = gravity->layout().spacing()[0];
    core::Vec3 const centre{0.013, -0.021, 0.008};
    core::Vec3 const x = core::Vec3::UnitX();
    auto energy = [&](double sep) {
        std::vector<core::Vec3> pos;
        std::vector<double> mass;
        if (world.rank() == 0) {
            pos = {centre - 0.5 * sep * x, centre + 0.5 * sep * x};
            mass = {1.0, 3.0};
        }
        Grains const grains{pos, {}, mass};
        gravity->update(grains);
        return gravity->potentialEnergy(grains);
    };
    double const r1 = 6.0 * h;
    double const r2 = 12.0 * h;
    double const change = energy(r2) - energy(r1);
    double const exact = -kG * 3.0 * (1.0 / r2 - 1.0 / r1);
    if (world.rank() == 0)
        std::printf("%s energy change %.5f, exact %.5f\n", name().c_str(), change, exact);
    EXPECT_NEAR(change, exact, 0.02 * exact);
}

TEST_P(PairForce, LoneGrainFeelsNoSelfForce) {
    double const h = gravity->layout().spacing()[0];
    std::vector<core::Vec3> pos;
    std::vector<double> mass;
    std::vector<double> radius;
    if (world.rank() == 0)
        for (double r : {0.0, 3.0 * h}) { // a point and a grain larger than a cell
            pos.push_back(core::Vec3{0.137, -0.052, 0.311} * (1.0 + r));
            mass.push_back(1.0);
            radius.push_back(r);
        }
    for (std::size_t i = 0; i < 2; ++i) {
        std::vector<core::Vec3> one;
        std::vector<double> m;
        std::vector<double> r;
        if (world.rank() == 0) {
            one.push_back(pos[i]);
            m.push_back(mass[i]);
            r.push_back(radius[i]);
        }
        Grains const grains{one, r, m};
        gravity->update(grains);
        std::vector<core::Vec3> g(one.size());
        gravity->accelerations(grains, g);
        // Compared with the pull of an equal mass 4 h away: the self-force comes only from
        // the boundary's lack of translation symmetry.
        double const reference = kG / (16.0 * h * h);
        if (world.rank() == 0) {
            std::printf("%s self-force / F(4h) = %.2e\n", name().c_str(),
                        g.front().norm() / reference);
            EXPECT_LT(g.front().norm(), 1e-3 * reference);
        }
    }
}

/// The mesh is translation invariant by whole cells in free space, open faces included: a
/// pair with one grain 2.5 cells from a face feels what it feels deep inside, and a lone grain
/// there no self-force. (PETSc's boundary values were Newton's, not the 7-point Laplacian's
/// own field: 5.7e-3 and 5.9e-3 F(4h) before, LatticeGreensFunction.hpp.)
TEST_P(PairForce, AnOpenFaceChangesNothing) {
    double const h = gravity->layout().spacing()[0];
    auto const N = gravity->layout().globalCells()[0];
    core::Vec3 const first = gravity->layout().centre({0, 0, 0});
    core::Vec3 const subCell{0.3 * h, 0.1 * h, -0.45 * h};
    core::Vec3 const apart = core::Vec3{-3.5, 4.0, 1.5} * h; // 5.52 cells
    auto const at = [&](std::int64_t i, std::int64_t j, std::int64_t k) -> core::Vec3 {
        return first +
               core::Vec3(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)) *
                   h +
               subCell;
    };
    core::Vec3 const inside = at(N / 2, N / 2, N / 2);
    core::Vec3 const nearFace = at(N - 3, N / 2 - 5, N / 2 + 3); // 2.5 cells from x = max
    Pair const ref = forces(inside, inside + apart, 1.0, 2.0);
    Pair const face = forces(nearFace, nearFace + apart, 1.0, 2.0);
    double const scale = ref.forceA.norm();
    if (world.rank() == 0)
        std::printf("%s near a face: pair force off by %.2e, lone grain %.2e F(4h)\n",
                    name().c_str(), (face.forceA - ref.forceA).norm() / scale,
                    forces(nearFace, nearFace + apart, 1.0, 0.0).forceA.norm() * 16.0 * h * h);
    else
        forces(nearFace, nearFace + apart, 1.0, 0.0);
    EXPECT_LT((face.forceA - ref.forceA).norm(), 2e-3 * scale) << name();
    EXPECT_LT((face.forceB - ref.forceB).norm(), 2e-3 * scale) << name();
    Pair const lone = forces(nearFace, nearFace + apart, 1.0, 0.0);
    EXPECT_LT(lone.forceA.norm(), 1e-3 * kG / (16.0 * h * h)) << name();
}

INSTANTIATE_TEST_SUITE_P(Kernels, PairForce,
                         ::testing::Values(std::tuple{Assignment::Cic, 2, PoissonMethod::Petsc},
                                           std::tuple{Assignment::Tsc, 4, PoissonMethod::Petsc},
                                           std::tuple{Assignment::Tsc, 4, PoissonMethod::Fft}),
                         [](auto const& p) {
                             return std::string(toString(std::get<0>(p.param))) + "_order" +
                                    std::to_string(std::get<1>(p.param)) + "_" +
                                    toString(std::get<2>(p.param));
                         });

} // namespace
