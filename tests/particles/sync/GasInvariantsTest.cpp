// A random gas drifts through 2x2x2, 3x3x3 and 4x2x1 forests (several blocks per rank at
// low rank counts), periodic and open, with NNS, SOS and hybrid (the latter two with a few
// boulders wider than a block among the grains): after every synchronisation
// the global invariants hold; in an open domain the grains that left are counted in
// SyncStats::leftDomain and are gone from every block.
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <algorithm>
#include <sstream>

using namespace regolith::particles;
using namespace regolith::particles::synctest;
using regolith::core::ReduceOp;

namespace {

struct GasCase {
    std::array<int, 3> blocks;
    bool periodic;
    SyncMethod method;
};

std::string name(GasCase const& c) {
    std::ostringstream s;
    s << methodName(c.method) << " " << c.blocks[0] << "x" << c.blocks[1] << "x" << c.blocks[2]
      << (c.periodic ? " periodic" : " open");
    return s.str();
}

/// Runs the gas; returns the number of grains that left the domain.
std::uint64_t runGas(GasCase const& c) {
    Comm world;
    AABB const domain{Vec3::Zero(), Vec3(8, 8, 8)};
    domain::BlockForest const forest(
        world, forestSpec(domain.min, domain.max, c.blocks, allAxes(c.periodic)));
    LocalParticles local(forest);
    ParticleSync sync(world, forest, SyncConfig{c.method, false});
    auto grains = randomGas(domain, 120, 0.2, 0.6, 1.0, 11);
    if (c.method != SyncMethod::NextNeighbour) {
        // Three boulders wider than the smallest block edge (SOS class under hybrid).
        for (ParticleInit g : randomGas(domain, 3, 2.5, 3.5, 1.0, 12)) {
            g.uid = makeUid(1, uidCounter(g.uid));
            grains.push_back(g);
        }
    }
    std::uint64_t alive = addAll(local, world, grains);
    EXPECT_EQ(alive, grains.size()) << name(c);
    sync.requireNnsApplicable(local);
    sync.syncUntilConverged(local);
    auto v = checkSyncInvariants(local, world, true);
    EXPECT_TRUE(v.empty()) << name(c) << " after set-up" << joined(v);

    double const dt = 0.1; // at most 0.17 per step: far below the smallest edge 2
    std::vector<Uid> gone;
    std::uint64_t leftTotal = 0;
    for (int step = 1; step <= 25; ++step) {
        drift(local, dt);
        std::vector<Uid> leaving;
        for (BlockParticles const& bp : local.blocks())
            bp.particles.forEachMaster([&](std::size_t i) {
                if (!forest.insideDomain(bp.particles.position(i)))
                    leaving.push_back(bp.particles.uid(i));
            });
        sync.sync(local);
        std::string const where = name(c) + " step " + std::to_string(step);
        std::uint64_t const left = world.allReduce(sync.lastStats().leftDomain, ReduceOp::Sum);
        std::vector<Uid> const leavingAll = gatherUids(world, leaving);
        EXPECT_EQ(left, leavingAll.size()) << where;
        leftTotal += left;
        alive -= leavingAll.size();
        EXPECT_EQ(globalMasters(local, world), alive) << where;
        gone.insert(gone.end(), leavingAll.begin(), leavingAll.end());
        std::sort(gone.begin(), gone.end());
        for (BlockParticles const& bp : local.blocks())
            for (Uid uid : bp.particles.uids())
                EXPECT_FALSE(std::binary_search(gone.begin(), gone.end(), uid))
                    << where << ": uid " << uid << " left the domain but is still in block "
                    << bp.block->id.toString();
        v = checkSyncInvariants(local, world, true);
        EXPECT_TRUE(v.empty()) << where << joined(v);
    }
    return leftTotal;
}

void runAll(SyncMethod method) {
    for (std::array<int, 3> blocks :
         {std::array{2, 2, 2}, std::array{3, 3, 3}, std::array{4, 2, 1}})
        for (bool periodic : {false, true}) {
            GasCase const c{blocks, periodic, method};
            std::uint64_t const left = runGas(c);
            if (periodic) {
                EXPECT_EQ(left, 0U) << name(c);
            } else {
                EXPECT_GT(left, 0U) << name(c) << ": the test should see grains leave";
            }
        }
}

} // namespace

TEST(GasInvariants, Nns) {
    runAll(SyncMethod::NextNeighbour);
}

TEST(GasInvariants, Sos) {
    runAll(SyncMethod::ShadowOwner);
}

TEST(GasInvariants, Hybrid) {
    runAll(SyncMethod::Hybrid);
}
