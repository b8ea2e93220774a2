// The mixing rules of unlike material types (particles/kernels/MaterialMixing.hpp): LAMMPS's
// pair_style granular convention, geometric means and the Hertz effective moduli.
#include "particles/kernels/MaterialMixing.hpp"

#include "core/Error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace regolith::particles;

namespace {

MaterialProperties material(double k, double e, double mu, double muR, double young = 0.0,
                            double nu = 0.0) {
    MaterialProperties m;
    m.stiffness = k;
    m.restitution = e;
    m.friction = mu;
    m.rollingFriction = muR;
    m.youngsModulus = young;
    m.poissonRatio = nu;
    return m;
}

} // namespace

TEST(MaterialMixing, LikePairsKeepTheirValuesExactly) {
    // 0.1 * 0.1 rounds: sqrt of it need not give 0.1 back; a like pair must.
    MaterialProperties const a = material(1e4 / 3.0, 0.1, 0.3, 0.07);
    LinearContactParams const p = mixLinear(a, a, {});
    EXPECT_EQ(p.stiffness, a.stiffness);
    EXPECT_EQ(p.tangentialStiffness, 2.0 / 7.0 * a.stiffness);
    EXPECT_EQ(p.restitution, a.restitution);
    EXPECT_EQ(p.friction, a.friction);
    EXPECT_EQ(p.rollingFriction, a.rollingFriction);
}

TEST(MaterialMixing, UnlikePairsTakeTheGeometricMean) {
    MaterialProperties const a = material(100.0, 0.9, 0.2, 0.0);
    MaterialProperties const b = material(400.0, 0.4, 0.8, 0.05);
    LinearContactParams const p = mixLinear(a, b, {});
    EXPECT_DOUBLE_EQ(p.stiffness, 200.0);
    EXPECT_DOUBLE_EQ(p.tangentialStiffness, 2.0 / 7.0 * 200.0);
    EXPECT_DOUBLE_EQ(p.restitution, 0.6);
    EXPECT_DOUBLE_EQ(p.friction, 0.4);
    EXPECT_EQ(p.rollingFriction, 0.0); // one side without rolling resistance: none
    RollingSpring spring;
    spring.enabled = true;
    EXPECT_TRUE(mixLinear(a, b, spring).rollingSpring.enabled);
}

TEST(MaterialMixing, HertzModuliFollowFromBothMaterials) {
    double const e1 = 7e10, nu1 = 0.25, e2 = 2e11, nu2 = 0.3;
    MaterialProperties const a = material(0.0, 0.8, 0.5, 0.0, e1, nu1);
    MaterialProperties const b = material(0.0, 0.2, 0.5, 0.0, e2, nu2);
    HertzMindlinParams const like = mixHertz(a, a, {});
    EXPECT_DOUBLE_EQ(like.effectiveYoungsModulus, e1 / (2.0 * (1.0 - nu1 * nu1)));
    EXPECT_DOUBLE_EQ(like.effectiveShearModulus, e1 / (4.0 * (2.0 - nu1) * (1.0 + nu1)));
    EXPECT_EQ(like.restitution, 0.8);
    HertzMindlinParams const ab = mixHertz(a, b, {});
    EXPECT_DOUBLE_EQ(ab.effectiveYoungsModulus,
                     1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2));
    EXPECT_DOUBLE_EQ(ab.restitution, 0.4);
    HertzMindlinParams const ba = mixHertz(b, a, {});
    EXPECT_EQ(ab.effectiveYoungsModulus, ba.effectiveYoungsModulus);
    EXPECT_EQ(ab.effectiveShearModulus, ba.effectiveShearModulus);
}

TEST(MaterialMixing, TableHoldsEveryPairSymmetrically) {
    std::vector<MaterialProperties> const types{material(100.0, 0.9, 0.2, 0.0),
                                                material(400.0, 0.4, 0.8, 0.0),
                                                material(900.0, 0.5, 0.5, 0.0)};
    auto const table = mixedTable<LinearContactParams>(types, {}, mixLinear);
    ASSERT_EQ(table.numTypes(), 3U);
    EXPECT_DOUBLE_EQ(table(0, 2).stiffness, 300.0);
    EXPECT_EQ(table(2, 0).stiffness, table(0, 2).stiffness);
    EXPECT_EQ(table(1, 1).friction, 0.8);
}

TEST(MaterialMixing, BadPoissonRatioIsRefused) {
    MaterialProperties const a = material(0.0, 0.8, 0.5, 0.0, 1e7, 0.6);
    try {
        (void)mixHertz(a, a, {});
        FAIL() << "expected an InputError";
    } catch (regolith::core::InputError const& e) {
        EXPECT_STREQ(e.what(), "contact.poisson_ratio = 0.6: expected a value in (-1, 0.5]");
    }
}
