// Barnes–Hut against the direct sum on the large bodies: the second paper's large
// agglomerate (38,358 grains, radii 20–60 m, 3,000 kg/m³) and a Plummer sphere of 10⁵ grains.
// The tree evaluates every grain; the exact field is summed for a deterministic sample of
// ~400 grains per rank (every k-th local grain), which keeps the reference at O(400 N) per
// rank. At θ = 0.5 with quadrupoles: median relative error ≤ 1e-3 and 99th percentile ≤ 1e-2
// on every rank count.
#include "gravity/tree/BarnesHut.hpp"
#include "tests/gravity/GravityTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

using namespace regolith;
using namespace regolith::testing;
namespace gt = regolith::gravity::tree;

namespace {

void expectTreeMatchesSampledDirect(gravity::samples::Body const& body, char const* name) {
    gravity::samples::Body const local = localSlab(world(), body);
    gt::TreeOptions options;
    options.theta = 0.5;
    gt::BarnesHut tree(world(), options);
    Field f(local.size());
    tree.evaluate(local.view(), f.out());

    // The sample: every k-th local grain, and the tree's field there.
    std::size_t const stride = std::max<std::size_t>(1, local.size() / 400);
    gravity::samples::Body sample;
    Field approx(0);
    for (std::size_t i = 0; i < local.size(); i += stride) {
        sample.push(local, i);
        approx.ax.push_back(f.ax[i]);
        approx.ay.push_back(f.ay[i]);
        approx.az.push_back(f.az[i]);
    }
    Field const exact = referenceField(sample, body, gravity::kNewtonG);
    gravity::ErrorStats const e =
        gravity::errorStats(world(), gravity::relativeErrors(approx.view(), exact.view()));
    if (world().rank() == 0)
        std::printf("%s (%zu grains) tree theta 0.5 on %d ranks: median %.3e  p99 %.3e\n", name,
                    body.size(), world().size(), e.median, e.p99);
    EXPECT_LE(e.median, 1e-3) << name;
    EXPECT_LE(e.p99, 1e-2) << name;
}

} // namespace

TEST(LargeBodies, PaperLargeAgglomerate) {
    expectTreeMatchesSampledDirect(testAgglomerate(38358), "agglomerate");
}

TEST(LargeBodies, PlummerSphere1e5) {
    expectTreeMatchesSampledDirect(gravity::samples::plummerSphere(100000, 1e12, 100.0, 5),
                                   "plummer");
}
