// The second paper's grid baselines against the direct sum: their error is measured (not
// bounded) and must fall as the grid is refined, from the paper's spacing (2.5 × the largest
// diameter) down to a quarter of it.
#include "gravity/baselines/GridMethods.hpp"

#include "core/Error.hpp"
#include "tests/gravity/GravityTestUtil.hpp"

#include <gtest/gtest.h>

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
