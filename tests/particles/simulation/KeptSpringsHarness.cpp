// The kept-spring tests' harness (KeptSpringsHarness.hpp).
#include "tests/particles/simulation/KeptSpringsHarness.hpp"

#include "core/mpi/Buffer.hpp"
#include "core/mpi/Comm.hpp"
#include "core/timing/TimerTree.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/simulation/DemStep.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace regolith::particles::kept_springs {

namespace {

long long sumOverRanks(core::Comm const& comm, ContactCounts const& counts) {
    long long sum = 0;
    for (std::vector<std::uint32_t> const& block : counts)
        for (std::uint32_t const n : block)
            sum += n;
    return comm.allReduce(sum, core::ReduceOp::Sum);
}

} // namespace

Scene packing(std::array<int, 3> blocks, double speed, double r) {
    Scene s;
    s.spec.domain = core::AABB{Vec3::Zero(), Vec3(6.0, 6.0, 8.0)};
    s.spec.rootBlocks = blocks;
    s.spec.periodic = {true, true, false};
    Uid uid = 0;
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 6; ++x, ++uid) {
                auto along = [&](int axis) { // a fixed scramble of the uid, no generator state
                    std::uint64_t const h = (uid * 2654435761u + 97u * axis) % 1000u;
                    return speed * (static_cast<double>(h) / 500.0 - 1.0);
                };
                s.grains.push_back(synctest::grain(uid, Vec3(0.5 + x, 0.5 + y, 0.6 + z), r,
                                                   Vec3(along(0), along(1), along(2))));
            }
    return s;
}

Outcome run(core::Comm const& comm, Scene const& scene, SyncConfig config, bool keep) {
    domain::BlockForest const forest(comm, scene.spec);
    LocalParticles local(forest);
    for (ParticleInit const& p : scene.grains)
        local.addMaster(p);
    LinearContactParams params;
    params.stiffness = 1000.0;
    params.tangentialStiffness = 2.0 / 7.0 * params.stiffness;
    params.restitution = 0.5;
    params.friction = 0.4;
    WallList walls;
    if (scene.walls) {
        walls.add(Vec3::Zero(), Vec3::UnitZ());
        walls.add(Vec3(0.0, 0.0, scene.spec.domain.max.z()), -Vec3::UnitZ());
    }
    ParticleSync sync(comm, forest, config);
    core::TimerTree timers;
    DemStepConfig c;
    c.dt = scene.dt;
    if (!scene.listed)
        c.detector = DetectorConfig{.skin = 0.0, .relativeSkin = 0.0, .widestRelativeSkin = 0.0};
    else if (scene.skin > 0.0)
        c.detector = DetectorConfig{.skin = scene.skin};
    else if (!scene.skinForTheScene)
        c.detector.widestRelativeSkin = 0.0;
    c.detector.sortByUid = scene.sortByUid;
    c.gravity = scene.gravity;
    c.keepContacts = scene.keepContacts;
    c.keepSprings = keep;
    DemStep dem(comm, sync, local, SpringDashpot(MaterialTable<LinearContactParams>(1, params)),
                VelocityVerlet{}, walls, c, timers);
    Outcome out;
    try {
        dem.setUp();
        for (int n = 1; n <= scene.steps; ++n) {
            dem.step(n % 50 == 0 ? DemStep::StepEnd::Complete : DemStep::StepEnd::Open);
            out.keptMost =
                std::max(out.keptMost, comm.allReduce(static_cast<long long>(dem.keptPairs()),
                                                      core::ReduceOp::Sum));
        }
        dem.step(DemStep::StepEnd::Open);
        ContactCounts const open = dem.contactsOfLastPass();
        dem.completeStep(); // writes the springs back after an Open step
        ContactCounts const complete = dem.contactsOfLastPass();
        out.contactsOpen = sumOverRanks(comm, open);
        out.contactsComplete = sumOverRanks(comm, complete);
        long long differ = 0;
        for (std::size_t b = 0; b < open.size(); ++b)
            for (std::size_t i = 0; i < open[b].size(); ++i)
                differ += open[b][i] != complete[b][i] ? 1 : 0;
        out.countsDiffer = comm.allReduce(differ, core::ReduceOp::Sum);
    } catch (core::Error const& e) {
        out.error = e.what();
    }
    out.rebuilds = comm.allReduce(static_cast<long long>(dem.listRebuilds()), core::ReduceOp::Sum);
    out.shifts = comm.allReduce(static_cast<long long>(dem.listShifts()), core::ReduceOp::Sum);

    // Gather every master (uid, x, v, w, live entries) on every rank.
    auto const stamp = static_cast<std::uint32_t>(dem.stepsDone());
    core::SendBuffer b;
    for (BlockParticles const& bp : local.blocks()) {
        ParticleStorage const& ps = bp.particles;
        ps.forEachMaster([&](std::size_t i) {
            std::vector<HistoryEntry> live;
            for (HistoryEntry const& e : ps.history(i))
                if (e.stamp == stamp)
                    live.push_back(e);
            b << ps.uid(i) << ps.position(i) << ps.velocity(i) << ps.angularVelocity(i)
              << static_cast<std::uint64_t>(live.size());
            for (HistoryEntry const& e : live)
                b << e.partner << e.spring;
        });
    }
    auto const bytes = b.bytes();
    std::string all = [&] {
        std::string joined;
        for (auto const& part : comm.gatherStrings(
                 std::string(reinterpret_cast<char const*>(bytes.data()), bytes.size()), 0))
            joined += part;
        return joined;
    }();
    comm.broadcast(all, 0);
    std::vector<std::byte> data(all.size());
    std::transform(all.begin(), all.end(), data.begin(),
                   [](char ch) { return static_cast<std::byte>(ch); });
    core::RecvBuffer in(std::move(data));
    struct Master {
        Uid uid;
        Vec3 x, v, w;
    };
    std::vector<Master> masters;
    while (!in.exhausted()) {
        Master m{};
        std::uint64_t entries = 0;
        in >> m.uid >> m.x >> m.v >> m.w >> entries;
        masters.push_back(m);
        for (std::uint64_t e = 0; e < entries; ++e) {
            LiveEntry l;
            l.owner = m.uid;
            in >> l.partner >> l.spring;
            out.live.push_back(l);
        }
    }
    std::sort(masters.begin(), masters.end(),
              [](Master const& p, Master const& q) { return p.uid < q.uid; });
    for (Master const& m : masters)
        for (Vec3 const* v : {&m.x, &m.v, &m.w})
            for (int d = 0; d < 3; ++d)
                out.bits.push_back(std::bit_cast<std::uint64_t>((*v)[d]));
    std::sort(out.live.begin(), out.live.end(), [](LiveEntry const& p, LiveEntry const& q) {
        return std::pair(p.owner, p.partner) < std::pair(q.owner, q.partner);
    });
    return out;
}

void expectSameState(Outcome const& x, Outcome const& y, std::size_t grains) {
    EXPECT_EQ(x.error, "");
    EXPECT_EQ(y.error, "");
    EXPECT_EQ(x.bits.size(), grains * 9u);
    EXPECT_TRUE(x.bits == y.bits) << "positions, velocities or spins differ";
    ASSERT_EQ(x.live.size(), y.live.size());
    EXPECT_GT(x.live.size(), 0u);       // contacts at the end, with springs to compare
    for (Outcome const* o : {&x, &y}) { // the contacts counted alike before the write-back
        EXPECT_EQ(o->contactsOpen, static_cast<long long>(o->live.size()));
        EXPECT_EQ(o->contactsComplete, static_cast<long long>(o->live.size()));
        EXPECT_EQ(o->countsDiffer, 0);
    }
    for (std::size_t k = 0; k < x.live.size(); ++k) {
        LiveEntry const& a = x.live[k];
        LiveEntry const& b = y.live[k];
        EXPECT_TRUE(a.owner == b.owner && a.partner == b.partner) << "entry " << k;
        for (int d = 0; d < 3; ++d)
            EXPECT_EQ(std::bit_cast<std::uint64_t>(a.spring[d]),
                      std::bit_cast<std::uint64_t>(b.spring[d]))
                << "spring of " << a.owner << "-" << a.partner;
    }
}

void expectSameBits(Outcome const& kept, Outcome const& histories, std::size_t grains) {
    expectSameState(kept, histories, grains);
    // The run kept springs beside the lists, and the lists were rebuilt or shifted (the
    // springs written back before syncs that might move a grain out of its block, or settled
    // again); the other kept none.
    EXPECT_GT(kept.keptMost, 0);
    EXPECT_EQ(histories.keptMost, 0);
    EXPECT_GT(kept.rebuilds + kept.shifts, 3);
}

void expectSameBits(core::Comm const& comm, Scene const& scene, SyncConfig config) {
    expectSameBits(run(comm, scene, config, true), run(comm, scene, config, false),
                   scene.grains.size());
}

} // namespace regolith::particles::kept_springs
