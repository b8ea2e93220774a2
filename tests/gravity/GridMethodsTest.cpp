// The second paper's grid baselines against the direct sum: their error is measured (not
// bounded) and must fall as the grid is refined, from the paper's spacing (2.5 × the largest
// diameter) down to a quarter of it.
#include "gravity/baselines/GridMethods.hpp"

#include "core/Error.hpp"
#include "tests/gravity/GravityTestUtil.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

using namespace regolith;
using namespace regolith::testing;
namespace gb = regolith::gravity::baselines;

namespace {

template <class Method>
void expectConvergence(char const* name, double theta) {
    auto const body = testAgglomerate(1000, 21);
    auto const local = localSlab(world(), body);
    Field const ref = referenceField(local, body, gravity::kNewtonG);
    double previous = 1e300;
    double const paperSpacing = 2.5 * 2.0 * 60.0;
    for (double const factor : {1.0, 0.5, 0.25, 0.125}) {
        gb::GridMethodOptions o;
        o.grid.spacing = factor * paperSpacing;
        o.grid.origin = core::Vec3(1.0, 2.0, 3.0);
        o.theta = theta;
        o.neighbourhood = 2.0 * o.grid.spacing;
        Method method(o);
        Field f(local.size());
        method.evaluate(world(), local.view(), f.out());
        auto const e = gravity::errorStats(world(), gravity::relativeErrors(f.view(), ref.view()));
        long long const nodes = world().allReduce(method.stats().nodes, core::ReduceOp::Sum);
        if (world().rank() == 0)
            std::printf("%s spacing %.1f m: median %.3e p99 %.3e (%lld nodes)\n", name,
                        o.grid.spacing, e.median, e.p99, nodes);
        EXPECT_LT(e.median, previous) << name << " spacing " << o.grid.spacing;
        previous = e.median;
    }
    EXPECT_LT(previous, 2e-2) << name << " at the finest grid";
}

} // namespace

TEST(GridMethods, OccupiedCellsConvergeToDirect) {
    expectConvergence<gb::OccupiedCells>("occupied-cells", 0.5);
}

TEST(GridMethods, TreeAtNodesConvergesToDirect) {
    expectConvergence<gb::TreeAtNodes>("tree-nodes", 0.3);
}

namespace {

/// The field of the node method `Method` (spacing 0.5, the paper's for radius 0.1) at the
/// grains (x, m) given on rank 0 (the other ranks hold none), with potentials.
template <class Method>
std::vector<std::array<double, 4>> nodeField(std::vector<core::Vec3> const& x,
                                             std::vector<double> const& mass) {
    bool const mine = world().rank() == 0;
    std::size_t const n = mine ? x.size() : 0;
    std::vector<double> px(n), py(n), pz(n), m(n), r(n, 0.1);
    for (std::size_t i = 0; i < n; ++i) {
        px[i] = x[i].x();
        py[i] = x[i].y();
        pz[i] = x[i].z();
        m[i] = mass[i];
    }
    gb::GridMethodOptions o;
    o.G = 1.0;
    o.grid.spacing = 0.5;
    o.neighbourhood = 1.0;
    Method method(o);
    std::vector<double> ax(n), ay(n), az(n), phi(n);
    method.evaluate(world(), {px, py, pz, m, r}, {ax, ay, az, phi});
    std::vector<std::array<double, 4>> out(n);
    for (std::size_t i = 0; i < n; ++i)
        out[i] = {ax[i], ay[i], az[i], phi[i]};
    return out;
}

template <class Method>
void expectNoSelfField(char const* name) {
    // A lone grain off the nodes: no field on itself (it was ~G m / h^2 = 2 here).
    auto const lone = nodeField<Method>({core::Vec3(0.37, -1.23, 0.61)}, {1.0});
    for (auto const& f : lone)
        for (double const v : f)
            EXPECT_NEAR(v, 0.0, 1e-12) << name;
    // Two grains 13.5 apart, masses 1 and 2: Newton's field within the interpolation error of
    // a smooth far field (it was ~3000 times too large), potential energy -G m1 m2 / d.
    core::Vec3 const a(-3.9, -3.9, -3.9), b(3.9, 3.9, 3.9);
    auto const pair = nodeField<Method>({a, b}, {1.0, 2.0});
    if (pair.empty())
        return;
    double const d = (b - a).norm();
    core::Vec3 const towardsB = (b - a) / d;
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(pair[0][static_cast<std::size_t>(k)], 2.0 / (d * d) * towardsB[k], 1e-5)
            << name;
        EXPECT_NEAR(pair[1][static_cast<std::size_t>(k)], -1.0 / (d * d) * towardsB[k], 1e-5)
            << name;
    }
    double const energy = 0.5 * (1.0 * pair[0][3] + 2.0 * pair[1][3]);
    EXPECT_NEAR(energy, -2.0 / d, 1e-4) << name;
}

} // namespace

TEST(GridMethods, NoGrainFeelsItsOwnField) {
    expectNoSelfField<gb::OccupiedCells>("occupied-cells");
    expectNoSelfField<gb::TreeAtNodes>("tree-nodes");
}

TEST(GridMethods, RefuseBadInputNamingTheKey) {
    gb::GridMethodOptions o;
    o.grid.spacing = 0.0;
    try {
        gb::OccupiedCells bad(o);
        ADD_FAILURE() << "spacing 0 accepted";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find("gravity.grid_spacing"), std::string::npos);
    }
    o.grid.spacing = 10.0;
    o.theta = 1.5;
    EXPECT_THROW(gb::TreeAtNodes{o}, core::InputError);
    o.theta = 0.5;
    o.neighbourhood = -1.0;
    EXPECT_THROW(gb::TreeAtNodes{o}, core::InputError);
}
