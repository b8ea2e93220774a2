// The solver around the physics: a periodic lattice against the analytic potential of a
// density wave; warm start from the previous potential; and bad input refused with a clear
// error naming the key (cells_per_block = 0, unknown PETSc solver, mixed periodicity, bad
// gradient order, mass outside the domain) or naming iterations and residual (no
// convergence).
#include "core/Error.hpp"
#include "gravity/GridGravity.hpp"
#include "tests/gravity/grid/GridTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

using namespace regolith;
using namespace regolith::gravity;

namespace {

constexpr double kPi = std::numbers::pi;

/// ρ = 1 + sin(kx) cos(ky) on the periodic box [-1, 1]^3 (k = π): ∇²φ = 4πG(ρ - 1) gives
/// φ = -4πG sin(kx) cos(ky) / (2k²). The 7-point stencil's eigenvalue for this mode differs
/// by (kh)²/12 ≈ 0.3 % at 32 cells per axis: tolerance 1 % of the amplitude.
TEST(GridSolver, PeriodicDensityWave) {
    core::Comm world;
    for (int perRank : {1, 8}) {
        auto const spec = test::cubeSpec(world, perRank, 32, {true, true, true});
        domain::BlockForest forest(world, spec);
        GridGravityOptions options;
        options.poisson.G = 1.0;
        GridGravity gravity(world, forest, spec.cellsPerBlock, options);
        auto const& layout = gravity.layout();
        auto const& n = layout.cellsPerBlock();
        auto forEach = [&](auto&& f) {
            for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
                for (int k = 0; k < n[2]; ++k)
                    for (int j = 0; j < n[1]; ++j)
                        for (int i = 0; i < n[0]; ++i) {
                            auto const& o = layout.origin(b);
                            f(b, i, j, k, layout.centre({o[0] + i, o[1] + j, o[2] + k}));
                        }
        };
        forEach([&](std::size_t b, int i, int j, int k, core::Vec3 const& x) {
            gravity.density().at(b, i, j, k) = 1.0 + std::sin(kPi * x[0]) * std::cos(kPi * x[1]);
        });
        gravity.solveFromDensity();
        double const amplitude = 4.0 * kPi / (2.0 * kPi * kPi);
        double err = 0.0;
        double gErr = 0.0;
        forEach([&](std::size_t b, int i, int j, int k, core::Vec3 const& x) {
            double const exact = -amplitude * std::sin(kPi * x[0]) * std::cos(kPi * x[1]);
            err = std::max(err, std::abs(gravity.potential().at(b, i, j, k) - exact));
            double const gx = amplitude * kPi * std::cos(kPi * x[0]) * std::cos(kPi * x[1]);
            gErr = std::max(gErr, std::abs(gravity.acceleration().at(b, i, j, k, 0) - gx));
        });
        err = world.allReduce(err, core::ReduceOp::Max);
        gErr = world.allReduce(gErr, core::ReduceOp::Max);
        EXPECT_LT(err, 0.01 * amplitude) << perRank << " blocks per rank";
        EXPECT_LT(gErr, 0.01 * amplitude * kPi) << perRank << " blocks per rank";
    }
}

/// A slowly moving pair (0.01 h per step): starting from the previous potential saves
/// iterations. Multigrid-preconditioned CG reduces the residual by a roughly fixed factor
/// per iteration, so a warm start saves about log(r0 / |b|) / log(rtol) of the work, where
/// r0 is the residual of the previous potential for the new density: measured 8 -> 5
/// iterations at rtol = 1e-6 (13 -> 9 at 1e-10); halving needs r0 / |b| < sqrt(rtol)
/// (bench/grid reports the numbers). Asserted: at least 2 iterations fewer, which fails if
/// the warm start is lost (the same count then).
TEST(GridSolver, WarmStartFromThePreviousPotential) {
    core::Comm world;
    auto const spec = test::cubeSpec(world, 2, 32, {false, false, false}, 2.0);
    domain::BlockForest forest(world, spec);
    GridGravityOptions options;
    options.poisson.G = 1.0;
    options.poisson.rtol = 1e-6;
    GridGravity gravity(world, forest, spec.cellsPerBlock, options);
    double const h = gravity.layout().spacing()[0];
    std::vector<int> iterations;
    for (int step = 0; step < 3; ++step) {
        std::vector<core::Vec3> pos;
        std::vector<double> mass;
        std::vector<double> radius;
        if (world.rank() == 0) {
            double const dx = 0.01 * h * step;
            pos = {core::Vec3{-0.5 + dx, 0.1, 0.0}, core::Vec3{0.4, -0.2 + dx, 0.3}};
            mass = {1.0, 2.0};
            radius = {2.0 * h, 3.0 * h};
        }
        iterations.push_back(gravity.update({pos, radius, mass}).iterations);
    }
    if (world.rank() == 0)
        std::printf("iterations cold %d, warm %d, %d\n", iterations[0], iterations[1],
                    iterations[2]);
    EXPECT_GT(iterations[0], 0);
    EXPECT_LE(iterations[1] + 2, iterations[0]);
    EXPECT_LE(iterations[2] + 2, iterations[0]);
}

/// Runs `make` and expects a core::InputError whose message contains `key`.
void expectInputError(std::function<void()> const& make, std::string const& key) {
    try {
        make();
        ADD_FAILURE() << "no error for " << key;
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
}

/// The FFT method through the same facade: potential and field of a smooth ball against the
/// PETSc method on the same cells, ghost layer included (both second order; they differ by
/// O(h²): measured 2.7e-2 of max |φ| and 5.3e-2 of max |g| here, the largest near the compact
/// mass; a wrong G, a missing boundary or an unscattered rank would be O(1)).
TEST(GridSolver, FftMethodAgreesWithPetsc) {
    core::Comm world;
    auto const spec = test::cubeSpec(world, 2, 32, {false, false, false}, 2.0);
    domain::BlockForest forest(world, spec);
    GridGravityOptions options;
    options.poisson.G = 1.0;
    options.poisson.rtol = 1e-8;
    GridGravity petsc(world, forest, spec.cellsPerBlock, options);
    options.poissonMethod = PoissonMethod::Fft;
    GridGravity fft(world, forest, spec.cellsPerBlock, options);
    std::vector<core::Vec3> pos;
    std::vector<double> mass;
    std::vector<double> radius;
    if (world.rank() == 0) // a ball of radius 0.5 = 4 h, off-centre
        for (int i = 0; i < 40; ++i) {
            double const t = 0.61803398875 * i;
            pos.push_back(core::Vec3{0.3 + 0.2 * std::cos(6.28 * t), 0.1 + 0.2 * std::sin(6.28 * t),
                                     -0.2 + 0.01 * i});
            mass.push_back(1.0);
            radius.push_back(0.3);
        }
    Grains const grains{pos, radius, mass};
    petsc.update(grains);
    fft.update(grains);
    double phiScale = 0.0;
    double phiDiff = 0.0;
    double gScale = 0.0;
    double gDiff = 0.0;
    auto const& layout = fft.layout();
    auto const& n = layout.cellsPerBlock();
    for (std::size_t b = 0; b < layout.localBlockCount(); ++b)
        for (int k = -1; k <= n[2]; ++k) // the ghost layer too (faces: boundary values)
            for (int j = -1; j <= n[1]; ++j)
                for (int i = -1; i <= n[0]; ++i) {
                    double const p = petsc.potential().at(b, i, j, k);
                    phiScale = std::max(phiScale, std::abs(p));
                    phiDiff = std::max(phiDiff, std::abs(fft.potential().at(b, i, j, k) - p));
                    if (i < 0 || j < 0 || k < 0 || i == n[0] || j == n[1] || k == n[2])
                        continue;
                    for (int c = 0; c < 3; ++c) {
                        double const gp = petsc.acceleration().at(b, i, j, k, c);
                        gScale = std::max(gScale, std::abs(gp));
                        gDiff =
                            std::max(gDiff, std::abs(fft.acceleration().at(b, i, j, k, c) - gp));
                    }
                }
    phiScale = world.allReduce(phiScale, core::ReduceOp::Max);
    phiDiff = world.allReduce(phiDiff, core::ReduceOp::Max);
    gScale = world.allReduce(gScale, core::ReduceOp::Max);
    gDiff = world.allReduce(gDiff, core::ReduceOp::Max);
    ASSERT_GT(phiScale, 0.0);
    EXPECT_LT(phiDiff / phiScale, 0.05);
    EXPECT_LT(gDiff / gScale, 0.1);
    if (world.rank() == 0)
        std::printf("fft against petsc: phi %.2e, g %.2e of the largest\n", phiDiff / phiScale,
                    gDiff / gScale);
}

TEST(GridSolver, BadInputNamesTheKey) {
    core::Comm world;
    auto spec = test::cubeSpec(world, 1, 16, {false, false, false});
    domain::BlockForest forest(world, spec);
    GridGravityOptions ok;
    expectInputError(
        [&] {
            GridGravity g(world, forest, {0, 16, 16}, ok);
        },
        "domain.cells_per_block");
    auto bad = ok;
    bad.poisson.petscOptions = "-ksp_type nosuch";
    expectInputError([&] { GridGravity g(world, forest, spec.cellsPerBlock, bad); },
                     "gravity.petsc.options");
    bad = ok;
    bad.gradientOrder = 3;
    expectInputError([&] { GridGravity g(world, forest, spec.cellsPerBlock, bad); },
                     "gravity.gradient_order");
    bad = ok;
    bad.poisson.G = -1.0;
    expectInputError([&] { GridGravity g(world, forest, spec.cellsPerBlock, bad); }, "gravity.G");
    auto mixed = test::cubeSpec(world, 1, 16, {true, false, false});
    domain::BlockForest mixedForest(world, mixed);
    expectInputError([&] { GridGravity g(world, mixedForest, mixed.cellsPerBlock, ok); },
                     "domain.periodic");
    auto periodic = test::cubeSpec(world, 1, 16, {true, true, true});
    domain::BlockForest periodicForest(world, periodic);
    bad = ok;
    bad.poissonMethod = PoissonMethod::Fft;
    expectInputError([&] { GridGravity g(world, periodicForest, periodic.cellsPerBlock, bad); },
                     "gravity.poisson");
    expectInputError([] { (void)parsePoissonMethod("multigrid"); }, "gravity.poisson");

    // Mass outside the domain, held by the last rank only: every rank gets its message.
    GridGravity gravity(world, forest, spec.cellsPerBlock, ok);
    std::vector<core::Vec3> pos;
    std::vector<double> mass;
    if (world.rank() == world.size() - 1) {
        pos.push_back(core::Vec3{0.2, 1.3, 0.0});
        mass.push_back(1.0);
    }
    expectInputError(
        [&] {
            gravity.update({pos, {}, mass});
        },
        "a grain at [0.2, 1.3, 0] lies outside the domain");
    // The good options still work afterwards (the bad solver's options were removed).
    pos.clear();
    mass.clear();
    if (world.rank() == 0) {
        pos.push_back(core::Vec3{0.2, 0.3, 0.0});
        mass.push_back(1.0);
    }
    EXPECT_NO_THROW(gravity.update({pos, {}, mass}));
}

void expectNonConvergence(std::string const& petscOptions) {
    core::Comm world;
    auto spec = test::cubeSpec(world, 1, 16, {false, false, false});
    domain::BlockForest forest(world, spec);
    GridGravityOptions options;
    options.poisson.petscOptions = petscOptions;
    GridGravity gravity(world, forest, spec.cellsPerBlock, options);
    std::vector<core::Vec3> pos;
    std::vector<double> mass;
    if (world.rank() == 0) {
        pos.push_back(core::Vec3{0.2, 0.3, 0.0});
        mass.push_back(1.0);
    }
    try {
        gravity.update({pos, {}, mass});
        ADD_FAILURE() << "a 2-iteration Jacobi-CG solve converged";
    } catch (core::InputError const& e) { // alike on every rank: one message, exit 2
        std::string const what = e.what();
        EXPECT_NE(what.find("did not converge"), std::string::npos) << what;
        EXPECT_NE(what.find("after 2 iterations"), std::string::npos) << what;
        EXPECT_NE(what.find("residual norm"), std::string::npos) << what;
    }
}

TEST(GridSolver, NonConvergenceNamesIterationsAndResidual) {
    // Also when PETSc is told to make it an error code (-ksp_error_if_not_converged): that was
    // an internal error on every rank, now the same collective input error.
    for (char const* extra : {"", " -ksp_error_if_not_converged"})
        expectNonConvergence(std::string("-ksp_max_it 2 -pc_type jacobi") + extra);
}

} // namespace
