// Presence of copies after every synchronisation call, checked against a brute-force truth
// that every rank computes alone: a random gas with radii up to several block edges moves
// through periodic and open forests with 1 to 6 blocks per axis; after each sync a block holds
// the copy (uid, image) iff copyNeeded says so, the master iff its box contains the centre,
// and every copy carries the master's position bit for bit. A forest on one subdomain holds no
// image through its wrapped faces (wrappedAxes).
#include "core/Error.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <string>
#include <tuple>

namespace regolith::particles {
namespace {

struct Case {
    SyncMethod method;
    int blocksPerAxis;
    double maxRadius;
    bool periodic;
};

/// Number of disagreements with the brute-force truth over 40 moves of 60 grains.
int presenceViolations(Case const& c) {
    core::Comm world;
    double const L = 30.0;
    domain::ForestSpec spec;
    spec.domain = core::AABB{core::Vec3::Zero(), core::Vec3::Constant(L)};
    spec.rootBlocks = {c.blocksPerAxis, c.blocksPerAxis, c.blocksPerAxis};
    spec.periodic = {c.periodic, c.periodic, c.periodic};
    domain::BlockForest forest(world, spec);
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{c.method, false});
    int const n = 60;
    std::mt19937 gen(7); // the same sequence on every rank
    std::uniform_real_distribution<double> pos(0.0, L), rad(0.2, c.maxRadius), vel(-0.4, 0.4);
    std::vector<core::Vec3> x(n), v(n);
    std::vector<double> r(n);
    std::vector<bool> alive(n, true);
    for (int i = 0; i < n; ++i) {
        x[i] = core::Vec3(pos(gen), pos(gen), pos(gen));
        r[i] = rad(gen);
        v[i] = core::Vec3(vel(gen), vel(gen), vel(gen));
        ParticleInit p;
        p.uid = static_cast<Uid>(i);
        p.position = x[i];
        p.radius = r[i];
        p.mass = 1.0;
        local.addMaster(p);
    }
    core::Vec3 const period = c.periodic ? core::Vec3::Constant(L) : core::Vec3::Zero();
    // No image through a wrapped face (one subdomain: the cells wrap instead).
    std::array<int, 3> span{0, 0, 0};
    for (std::size_t a = 0; a < 3; ++a)
        span[a] = c.periodic && !wrappedAxes(forest)[a] ? 1 : 0;
    int bad = 0;
    for (int step = 0; step < 40; ++step) {
        if (step == 0)
            sync.syncUntilConverged(local);
        else
            sync.sync(local);
        for (int i = 0; i < n; ++i) {
            alive[i] = alive[i] && forest.insideDomain(x[i]);
            if (alive[i])
                x[i] = forest.wrap(x[i]);
        }
        for (BlockParticles const& bp : local.blocks()) {
            ParticleStorage const& ps = bp.particles;
            std::size_t held = 0;
            for (int i = 0; i < n; ++i) {
                for (int a = -span[0]; a <= span[0]; ++a)
                    for (int b = -span[1]; b <= span[1]; ++b)
                        for (int d = -span[2]; d <= span[2]; ++d) {
                            CopyImage const k{static_cast<std::int8_t>(a),
                                              static_cast<std::int8_t>(b),
                                              static_cast<std::int8_t>(d)};
                            bool const need =
                                alive[i] && copyNeeded(bp.block->aabb, x[i], k, r[i], period);
                            std::size_t const j = ps.find(static_cast<Uid>(i), k);
                            bool const has = j != ParticleStorage::kNotFound;
                            held += has ? 1 : 0;
                            EXPECT_EQ(need, has) << "step " << step << " uid " << i << " image "
                                                 << a << b << d << " block " << bp.block->id.raw();
                            bad += need != has ? 1 : 0;
                            if (!has)
                                continue;
                            bool const master = isZero(k) && bp.block->aabb.contains(x[i]);
                            EXPECT_EQ(ps.flags(j).isMaster(), master) << "uid " << i;
                            EXPECT_TRUE(ps.position(j) == x[i]) << "uid " << i;
                            bad += ps.flags(j).isMaster() != master ? 1 : 0;
                        }
            }
            EXPECT_EQ(held, ps.size()); // nothing else is held
        }
        for (BlockParticles& bp : local.blocks())
            bp.particles.forEachMaster(
                [&](std::size_t j) { bp.particles.position(j) += v[bp.particles.uid(j)]; });
        for (int i = 0; i < n; ++i)
            x[i] += v[i];
    }
    return bad;
}

class SyncPresence : public ::testing::TestWithParam<Case> {};

TEST_P(SyncPresence, CopiesExactlyWhereGrainsOverlap) {
    EXPECT_EQ(presenceViolations(GetParam()), 0);
}

INSTANTIATE_TEST_SUITE_P(
    Forests, SyncPresence,
    ::testing::Values(
        Case{SyncMethod::NextNeighbour, 3, 1.0, true},
        Case{SyncMethod::NextNeighbour, 3, 1.0, false},
        Case{SyncMethod::NextNeighbour, 1, 1.0, true}, // block its own neighbour
        Case{SyncMethod::NextNeighbour, 2, 1.0, true}, Case{SyncMethod::ShadowOwner, 1, 5.0, true},
        Case{SyncMethod::ShadowOwner, 2, 3.0, true},
        Case{SyncMethod::ShadowOwner, 6, 7.0, true}, // grains span 3 layers
        Case{SyncMethod::ShadowOwner, 6, 7.0, false}, Case{SyncMethod::Hybrid, 6, 7.0, true},
        Case{SyncMethod::Hybrid, 5, 7.0, false}, Case{SyncMethod::Hybrid, 2, 5.0, true}));

TEST(SyncRefusal, NnsRefusesAGrainLargerThanItsBlocks) {
    core::Comm world;
    domain::ForestSpec spec;
    spec.domain = core::AABB{core::Vec3::Zero(), core::Vec3::Constant(30.0)};
    spec.rootBlocks = {3, 3, 3};
    spec.periodic = {true, true, true};
    domain::BlockForest forest(world, spec);
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{SyncMethod::NextNeighbour, false});
    ParticleInit p;
    p.uid = 4242;
    p.position = core::Vec3(15, 15, 15);
    p.radius = 12.0;
    p.mass = 1.0;
    local.addMaster(p);
    try {
        sync.requireNnsApplicable(local);
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        std::string const m = e.what();
        EXPECT_NE(m.find("uid 4242"), std::string::npos) << m;
        EXPECT_NE(m.find("radius 12"), std::string::npos) << m;
        EXPECT_NE(m.find("edge 10"), std::string::npos) << m;
        EXPECT_NE(m.find("\"sos\""), std::string::npos) << m;
    }
}

} // namespace
} // namespace regolith::particles
