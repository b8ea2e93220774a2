// The octree's structure and moments: every grain in exactly one leaf, contiguous children
// after their parent, root mass / centre of mass / quadrupole / b_max against brute force,
// and a corrupt locally essential tree refused.
#include "gravity/tree/Octree.hpp"

#include "core/Error.hpp"
#include "gravity/tree/LocallyEssentialTree.hpp"
#include "tests/gravity/GravityTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace regolith;
namespace gt = regolith::gravity::tree;

TEST(Octree, PartitionsTheGrainsAndKeepsChildrenAfterParents) {
    auto const body = gravity::samples::plummerSphere(3000, 1e12, 100.0, 8);
    gt::Octree const tree = gt::Octree::build(body.view(), {});
    auto const& nodes = tree.nodes();
    std::vector<int> seen(body.size(), 0);
    for (std::size_t k = 0; k < nodes.size(); ++k) {
        gt::TreeNode const& c = nodes[k];
        if (c.childCount == 0) {
            EXPECT_LE(c.count(), 8);
            for (std::int32_t i = c.begin; i < c.end; ++i)
                ++seen[static_cast<std::size_t>(tree.order()[static_cast<std::size_t>(i)])];
            continue;
        }
        EXPECT_GT(c.firstChild, static_cast<std::int32_t>(k));
        std::int32_t expectBegin = c.begin;
        for (std::int32_t j = 0; j < c.childCount; ++j) {
            gt::TreeNode const& s = nodes[static_cast<std::size_t>(c.firstChild + j)];
            EXPECT_EQ(s.begin, expectBegin); // children tile the parent's grain range
            expectBegin = s.end;
            EXPECT_DOUBLE_EQ(s.half, 0.5 * c.half);
        }
        EXPECT_EQ(expectBegin, c.end);
    }
    for (int const n : seen)
        EXPECT_EQ(n, 1);
}

TEST(Octree, RootMomentsMatchBruteForce) {
    auto const body = regolith::testing::testAgglomerate(500, 3);
    gt::Octree const tree = gt::Octree::build(body.view(), {});
    gt::TreeNode const& root = tree.nodes().front();
    double m = 0.0;
    core::Vec3 c = core::Vec3::Zero();
    for (std::size_t i = 0; i < body.size(); ++i) {
        m += body.m[i];
        c += body.m[i] * core::Vec3(body.x[i], body.y[i], body.z[i]);
    }
    c /= m;
    EXPECT_NEAR(root.mass, m, 1e-12 * m);
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(root.com[a], c[a], 1e-9);
    double q[6] = {0, 0, 0, 0, 0, 0};
    double bmax = 0.0;
    for (std::size_t i = 0; i < body.size(); ++i) {
        core::Vec3 const d = core::Vec3(body.x[i], body.y[i], body.z[i]) - c;
        double const d2 = d.squaredNorm();
        q[0] += body.m[i] * (3 * d.x() * d.x() - d2);
        q[1] += body.m[i] * (3 * d.y() * d.y() - d2);
        q[2] += body.m[i] * (3 * d.z() * d.z() - d2);
        q[3] += body.m[i] * 3 * d.x() * d.y();
        q[4] += body.m[i] * 3 * d.x() * d.z();
        q[5] += body.m[i] * 3 * d.y() * d.z();
        bmax = std::max(bmax, std::sqrt(d2));
    }
    double const scale = std::abs(q[0]) + std::abs(q[1]) + std::abs(q[2]);
    for (int a = 0; a < 6; ++a)
        EXPECT_NEAR(root.quad[a], q[a], 1e-9 * scale) << a;
    // b_max is exact (the largest distance from the com to a grain).
    EXPECT_GE(root.bmax, bmax * (1.0 - 1e-12));
    EXPECT_LE(root.bmax, bmax * (1.0 + 1e-12));
    EXPECT_NEAR(root.quad[0] + root.quad[1] + root.quad[2], 0.0, 1e-9 * scale); // traceless
}

TEST(Octree, CorruptLocallyEssentialTreeIsRefused) {
    gt::LocallyEssentialTree let;
    let.nodes.resize(1);
    let.nodes[0].childCount = 3;
    let.nodes[0].firstChild = 1; // children beyond the end
    core::SendBuffer out;
    gt::pack(out, let);
    core::RecvBuffer in(out.release());
    EXPECT_THROW((void)gt::unpackLocallyEssentialTree(in), core::Error);
}
