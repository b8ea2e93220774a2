// The batched orientation update (rotateMoving) against the per-grain one (rotate): the same
// bits lane by lane, whatever path each grain takes.
#include "particles/integration/Rotation.hpp"

#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace regolith::particles;
using namespace regolith::particles::test;

namespace {

/// A random unit-ish quaternion: normalised, then nudged off |q| = 1 by a few ulps or (for
/// some grains) by enough that rotate() normalises.
regolith::core::Quat randomOrientation(std::mt19937_64& rng, bool drifted) {
    std::normal_distribution<double> n(0.0, 1.0);
    regolith::core::Quat q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    if (drifted)
        q.coeffs() *= 1.0 + 1e-12;
    return q;
}

} // namespace

TEST(Rotation, BatchedUpdateIsBitwiseThePerGrainOne) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double const dt = 0.01;
    ParticleStorage ps;
    // 200 grains: more than three batches of 64 and a partial one; every path of rotate().
    for (int k = 0; k < 200; ++k) {
        ParticleInit p = sphere(static_cast<Uid>(k + 1), Vec3(k, 0, 0), 0.5, 1.0);
        if (k % 17 == 3)
            p.flags = Flag::Shadow; // not moved: its master rotates it
        if (k % 19 == 5)
            p.flags = Flag::Fixed;
        p.orientation = randomOrientation(rng, k % 5 == 0);
        Vec3 w(u(rng), u(rng), u(rng));
        if (k % 11 == 0)
            w = Vec3::Zero(); // no rotation at all
        if (k % 13 == 1)
            w *= 300.0; // |w| dt > 1e-2: the closed form with sin and cos
        p.angularVelocity = w;
        ps.add(p);
    }
    ParticleStorage const initial = ps;
    ParticleStorage expected = ps;
    for (std::size_t i = 0; i < ps.size(); ++i)
        if (!ps.flags(i).isShadow() && !ps.flags(i).isFixed()) {
            regolith::core::Quat q = expected.orientation(i);
            rotate(q, expected.angularVelocity(i), dt);
            expected.setOrientation(i, q);
        }
    rotateMoving(ps, dt);
    for (std::size_t i = 0; i < ps.size(); ++i) {
        EXPECT_EQ(ps.orientation(i).coeffs(), expected.orientation(i).coeffs()) << "grain " << i;
        bool const turns =
            !ps.flags(i).isShadow() && !ps.flags(i).isFixed() && !ps.angularVelocity(i).isZero(0.0);
        EXPECT_EQ(ps.orientation(i).coeffs() != initial.orientation(i).coeffs(), turns)
            << "grain " << i;
        if (turns) { // the drifted ones were normalised on the way
            EXPECT_NEAR(ps.orientation(i).squaredNorm(), 1.0, 1e-14) << "grain " << i;
        }
    }
}
