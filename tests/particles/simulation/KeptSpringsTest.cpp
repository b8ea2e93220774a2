// The tangential springs the Verlet lists keep beside their pairs deep inside a block
// (ContactDetector, "Springs kept beside the list"; DemStepConfig::keepSprings): a packing that
// starts compressed, flies apart, falls and settles, on several block layouts and ranks, with
// mostly Open steps (the springs stay beside the lists across steps and are written back
// before syncs that may migrate a grain, at Complete steps and at the end), must end with the
// same bits as the run that keeps every spring in the grains' histories: positions,
// velocities, spins, and every live history entry.
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

using namespace regolith;
using namespace regolith::particles;
using core::Vec3;

namespace {

constexpr double kRadius = 0.505; // spacing 1: every neighbour overlaps by 0.01 at first

/// A live history entry of a master, as gathered.
struct LiveEntry {
    Uid owner = kInvalidUid, partner = kInvalidUid;
    Vec3 spring;
};

struct Outcome {
    std::vector<std::uint64_t> bits; ///< every master's x, v, w in uid order, as bits
    std::vector<LiveEntry> live;     ///< entries stamped by the last pass, by (owner, partner)
    long long keptMost = 0;          ///< most pairs kept in one step, over all ranks
    long long twinsMost = 0;         ///< most face pairs settled in one step, over all ranks
    long long rebuilds = 0;
    long long shifts = 0; ///< lists shifted with the grains' drift instead of rebuilt
    std::string error;
};

struct Scene {
    domain::ForestSpec spec;
    std::vector<ParticleInit> grains;
    bool walls = true; ///< a floor and a ceiling (z = 0 and the domain's top)
    Vec3 gravity = Vec3(0.0, 0.0, -2.0);
    double dt = 0.002;
    double skin = 0.0; ///< the Verlet skin; 0: a quarter of the radius (DemStep's default)
    /// With skin 0: let the skin widen for the scene as DemStep's default does (ContactDetector,
    /// "A skin for the scene"); the scenes below are built for a quarter of the radius.
    bool skinForTheScene = false;
    int steps = 300;
    bool keepContacts = false; ///< DemStepConfig::keepContacts (false: the driver's setting)
    bool sortByUid = false;    ///< DetectorConfig::sortByUid (no fused list path)
    bool listed = true;        ///< false: no Verlet list (every step a linked-cell pass)
};

/// 6 x 6 x 4 grains on an sc lattice of spacing 1 in [0, 6]^2 x [0, 8], periodic in x and y,
/// floor and ceiling, gravity -2 along z, velocities in [-speed, speed] from the uid, radius
/// `r`.
Scene packing(std::array<int, 3> blocks, double speed = 0.3, double r = kRadius) {
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
            out.twinsMost =
                std::max(out.twinsMost, comm.allReduce(static_cast<long long>(dem.faceTwins()),
                                                       core::ReduceOp::Sum));
        }
        dem.step(DemStep::StepEnd::Open);
        dem.completeStep(); // writes the springs back after an Open step
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

/// Both runs went through and end with the same bits: every master's x, v, w and every live
/// history entry (there are some).
void expectSameState(Outcome const& x, Outcome const& y, std::size_t grains) {
    EXPECT_EQ(x.error, "");
    EXPECT_EQ(y.error, "");
    EXPECT_EQ(x.bits.size(), grains * 9u);
    EXPECT_TRUE(x.bits == y.bits) << "positions, velocities or spins differ";
    ASSERT_EQ(x.live.size(), y.live.size());
    EXPECT_GT(x.live.size(), 0u); // contacts at the end, with springs to compare
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

/// The runs with and without kept springs of `scene` end with the same bits.
void expectSameBits(core::Comm const& comm, Scene const& scene, SyncConfig config) {
    expectSameBits(run(comm, scene, config, true), run(comm, scene, config, false),
                   scene.grains.size());
}

TEST(KeptSprings, ChangeNoBitOnAnyLayout) {
    core::Comm const world;
    for (bool reproducible : {true, false}) {
        for (std::array<int, 3> blocks :
             {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{1, 3, 1}, std::array<int, 3>{2, 2, 1},
              std::array<int, 3>{3, 2, 2}}) {
            SCOPED_TRACE(::testing::Message() << "reproducible " << reproducible << ", blocks "
                                              << blocks[0] << "x" << blocks[1] << "x" << blocks[2]);
            SyncConfig const config{SyncMethod::Hybrid, reproducible};
            expectSameBits(world, packing(blocks), config);
            // Every neighbour overlapping by 0.2, more than the skin (0.15): evaluated untested
            // while listed (PairMode::KeptPressed), until the packing flies apart.
            expectSameBits(world, packing(blocks, 0.3, 0.6), config);
            // The skin chosen for the scene: the overlapping packing lists its six neighbours
            // with a wider one (and rebuilds less often).
            Scene wider = packing(blocks, 0.3, 0.6);
            wider.skinForTheScene = true;
            expectSameState(run(world, wider, config, true), run(world, wider, config, false),
                            wider.grains.size());
        }
    }
}

TEST(KeptSprings, ChangeNoBitWhileContactsOutliveRebuilds) {
    // A pressed packing sliding down a ramp along x and y (as scene B's): its lists are rebuilt
    // every few steps while most contacts last, pairs cross block faces and come near them, and
    // every rebuild's kept springs must come back whole from the previous list's.
    core::Comm const world;
    for (std::array<int, 3> blocks : {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{3, 2, 2}}) {
        SCOPED_TRACE(::testing::Message()
                     << "blocks " << blocks[0] << "x" << blocks[1] << "x" << blocks[2]);
        Scene sliding = packing(blocks, 0.05, 0.52);
        sliding.gravity = Vec3(6.0, 3.0, -2.0);
        for (ParticleInit& g : sliding.grains)
            g.velocity += Vec3(1.0, 0.5, 0.0);
        sliding.steps = 200;
        Outcome const kept = run(world, sliding, SyncConfig{SyncMethod::Hybrid, false}, true);
        expectSameBits(kept, run(world, sliding, SyncConfig{SyncMethod::Hybrid, false}, false),
                       sliding.grains.size());
        // Mostly shifted with the drift (ContactDetector::beforeSync), sometimes rebuilt.
        EXPECT_GT(kept.shifts, 10);
        EXPECT_GT(kept.rebuilds, 0);
        // The contacts of the shifted lists are those of a linked-cell pass every step: the
        // same bits where the forces are summed by uid.
        SyncConfig const reproducible{SyncMethod::Hybrid, true};
        Scene cells = sliding;
        cells.listed = false;
        Outcome const shifted = run(world, sliding, reproducible, true);
        expectSameState(shifted, run(world, cells, reproducible, false), sliding.grains.size());
        EXPECT_GT(shifted.shifts, 10);
    }
}

TEST(KeptSprings, ChangeNoBitWithContactsKeptOrSortedByUid) {
    // Kept contacts: the list hands each contact found, with its kept spring. Sorted by uid:
    // contacts are handed over after the sort, with the histories (the springs stay there).
    core::Comm const world;
    for (double r : {kRadius, 0.6}) {
        SCOPED_TRACE(::testing::Message() << "radius " << r);
        Scene kept = packing({2, 2, 1}, 0.3, r);
        kept.keepContacts = true;
        expectSameBits(world, kept, SyncConfig{SyncMethod::Hybrid, false});
        Scene sorted = packing({2, 2, 1}, 0.3, r);
        sorted.sortByUid = true;
        expectSameBits(world, sorted, SyncConfig{SyncMethod::Hybrid, false});
    }
}

TEST(KeptSprings, ChangeNoBitWhenAStepOutrunsTheSkin) {
    // A skin of 0.01 and steps of 0.005: a colliding pair, settled deeper than the half skin
    // inside its block, crosses the block face x = 2 in one step during the contact, in the
    // synchronisation before any list notices: its spring, grown by the sliding (relative
    // velocity 0.3 along x) since the last rebuild, must be back in its history before
    // (DemStep: ContactDetector::beforeSync). Contact from step ~8 to ~19, the face at ~14.
    core::Comm const world;
    Scene pair;
    pair.spec.domain = core::AABB{Vec3::Zero(), Vec3(6.0, 6.0, 6.0)};
    pair.spec.rootBlocks = {3, 1, 1};
    pair.grains = {synctest::grain(1, Vec3(1.71, 3.0, 3.0), kRadius, Vec3(4.0, 0.0, 0.0)),
                   synctest::grain(2, Vec3(1.71, 4.03, 3.0), kRadius, Vec3(4.3, -0.5, 0.0))};
    pair.walls = false;
    pair.gravity = Vec3::Zero();
    pair.dt = 0.005;
    pair.skin = 0.01;
    pair.steps = 16; // ends during the contact
    expectSameBits(world, pair, SyncConfig{SyncMethod::Hybrid, false});
    Scene fast = packing({3, 2, 2}, 3.0);
    fast.dt = 0.005;
    fast.skin = 0.01;
    expectSameBits(world, fast, SyncConfig{SyncMethod::Hybrid, false});
}

TEST(KeptSprings, FacePairsOfASpanningRegionChangeNoBit) {
    // A block spanning the periodic domain along an axis (the whole domain, or one of three
    // strips along y, each spanning x) settles the instance of each pair across such a face
    // whose i is i's master, and drops its twin (ContactDetector, "Pairs across a periodic
    // face"); blocks that tile the domain along every axis settle none. In reproducible mode the
    // layouts must end with the same bits: a face contact doubled or missed shows, and so does a
    // strip's settled pair that another strip evaluates too (on several ranks, or on one with a
    // block per strip). A drift
    // carries the grains across the x and y faces while they touch: settled face pairs die as
    // grains wrap (their kept springs go back to the grains' copies by uid), and twins arrive
    // as grains start to cross a face (drifting down x and y: the lower uid of a face pair,
    // near the lower face, moves towards it), to be dropped while the settled pair lives.
    core::Comm const world;
    for (bool keep : {true, false}) {
        for (double r : {kRadius, 0.6}) {
            for (double drift : {2.0, -2.0}) {
                SCOPED_TRACE(::testing::Message()
                             << "springs kept " << keep << ", radius " << r << ", drift " << drift);
                Scene one = packing({1, 1, 1}, 0.3, r);
                Scene strips = packing({1, 3, 1}, 0.3, r);
                Scene tiled = packing({3, 2, 1}, 0.3, r);
                for (Scene* s : {&one, &strips, &tiled})
                    for (ParticleInit& g : s->grains)
                        g.velocity += Vec3(drift, 0.65 * drift, 0.0);
                SyncConfig const config{SyncMethod::Hybrid, true};
                Outcome const a = run(world, one, config, keep);
                Outcome const s = run(world, strips, config, keep);
                Outcome const b = run(world, tiled, config, keep);
                EXPECT_GT(a.twinsMost, 0);
                if (r > kRadius) { // j's copies reach into a strip by more than the half skin
                    EXPECT_GT(s.twinsMost, 0);
                }
                EXPECT_EQ(b.twinsMost, 0);
                expectSameState(a, b, one.grains.size());
                expectSameState(s, b, one.grains.size());
            }
        }
    }
}

TEST(KeptSprings, AFacePairsTwinArrivingWhileItLivesIsDropped) {
    // A small grain i (lower uid) touches a large grain j's image across the face x = 0 at a
    // slant, the two drifting towards -x together: the list settles (i's master, j's image)
    // while i's ball does not reach the face, as j's image reaches deep into the block. Then i's
    // ball crosses the face (i's image arrives, with the twin pair) and, before the list is
    // rebuilt, so does the contact point (all in the list's first 20 steps, checked below):
    // the contact-point rule would now pick the twin. It must stay dropped, or the contact is
    // evaluated twice (ContactDetector, "Pairs across a periodic face"). Three small grains far
    // off make j a large sphere and the skin small (0.125).
    core::Comm const world;
    double const cosA = 0.97, sinA = std::sqrt(1.0 - cosA * cosA);
    Vec3 const n(-cosA, sinA, 0.0);         // from i towards j's image
    double const reach = 0.5 + 2.0 - 0.005; // touching by 0.005, i approaching at 0.2
    Vec3 const xi(0.505, 4.0, 4.0);
    Vec3 const xj = xi + reach * n + Vec3(8.0, 0.0, 0.0);
    Vec3 const drift(-1.0, 0.0, 0.0);
    auto scene = [&](std::array<int, 3> blocks) {
        Scene s;
        s.spec.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
        s.spec.rootBlocks = blocks;
        s.spec.periodic = {true, true, false};
        s.walls = false;
        s.gravity = Vec3::Zero();
        s.steps = 19;
        s.grains = {synctest::grain(1, xi, 0.5, Vec3(drift + 0.2 * n)),
                    synctest::grain(2, xj, 2.0, drift)};
        for (Uid u = 3; u <= 5; ++u)
            s.grains.push_back(
                synctest::grain(u, Vec3(4.0, 1.0, 1.5 * static_cast<double>(u)), 0.5, drift));
        return s;
    };
    SyncConfig const config{SyncMethod::Hybrid, true};
    for (bool keep : {true, false}) {
        SCOPED_TRACE(::testing::Message() << "springs kept " << keep);
        Outcome const a = run(world, scene({1, 1, 1}), config, keep);
        Outcome const b = run(world, scene({2, 2, 1}), config, keep);
        EXPECT_EQ(a.twinsMost, 1);
        EXPECT_EQ(b.twinsMost, 0);
        EXPECT_EQ(a.rebuilds, 1); // one list: i's image and the point crossed during its life
        expectSameState(a, b, 5);
    }
}

} // namespace
