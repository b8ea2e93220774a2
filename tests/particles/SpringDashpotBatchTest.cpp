// The batched spring-dashpot evaluation (SpringDashpotBatch, BatchedSpringDashpot) against
// evaluatePair one contact at a time: the same sink calls with the same bits, and the same
// springs and stamps in the histories, over several passes of a dense random pack with two
// materials and with one (its parameters constants in the lanes), sliding and sticking contacts,
// rolling resistance, springs that are zero, tiny, along the normal or far beyond the Coulomb
// limit, and a pair met twice in one pass.
#include "particles/kernels/SpringDashpotBatch.hpp"

#include "particles/detection/ContactDetector.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "tests/particles/ParticleTestUtil.hpp"
#include "tests/particles/PeriodicTestUtil.hpp"
#include "tests/particles/SharesTestUtil.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <random>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;

namespace {

/// Types 0 and 1: (0, 0) frictional with rolling resistance, (0, 1) without a tangential
/// spring (k_t = 0), (1, 1) nearly frictionless (slides at once). With `modelC`, (0, 0) has
/// model C's rolling spring (default k_r and damping), (0, 1) one with a given k_r and a damping
/// ratio beyond the dashpot's cap, and (1, 1) model A (mu_r = 0).
SpringDashpot twoMaterials(bool modelC = false) {
    MaterialTable<LinearContactParams> table(2);
    LinearContactParams p;
    p.stiffness = 2000.0;
    p.tangentialStiffness = 600.0;
    p.restitution = 0.7;
    p.friction = 0.5;
    p.rollingFriction = 0.05;
    p.rollingSpring.enabled = modelC;
    table.set(0, 0, p);
    LinearContactParams q = p;
    q.tangentialStiffness = 0.0;
    q.restitution = 0.4;
    q.rollingFriction = 0.3;
    q.rollingSpring.stiffness = 400.0;
    q.rollingSpring.dampingRatio = 50.0;
    table.set(0, 1, q);
    LinearContactParams s = p;
    s.stiffness = 5000.0;
    s.friction = 0.01;
    s.rollingFriction = 0.0;
    s.rollingSpring = RollingSpring{};
    s.tangentialDampingRatio = 0.3;
    table.set(1, 1, s);
    return SpringDashpot{table};
}

ParticleStorage randomPack(std::uint64_t seed, std::size_t n, double box) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    ParticleStorage ps;
    for (std::size_t k = 0; k < n; ++k) {
        ParticleInit p =
            sphere(makeUid(0, k + 1), box * Vec3(u(rng), u(rng), u(rng)), 0.35 + 0.3 * u(rng),
                   1.0 + u(rng), Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
        p.angularVelocity = 6.0 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        p.type = static_cast<std::uint32_t>(k % 3 == 0 ? 1 : 0);
        ps.add(p);
    }
    return ps;
}

/// Springs of every kind the scalar code branches on, on the first contacts' histories (with
/// `rolling`, model C's rolling springs too, in another order).
void seedSprings(ParticleStorage& ps, std::vector<Contact> const& pairs, bool rolling = false) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (std::size_t k = 0; k < (rolling ? 2 : 1) * pairs.size(); ++k) {
        Contact const& c = pairs[k % pairs.size()];
        bool const second = k >= pairs.size();
        Vec3& s = ps.history(c.i).touch(second ? rollingKey(ps.uid(c.j)) : ps.uid(c.j), 0).spring;
        switch ((k + (second ? 2 : 0)) % 5) {
        case 0:
            s = Vec3(u(rng), u(rng), u(rng)) * 1e-3;
            break; // sticks
        case 1:
            s = Vec3(u(rng), u(rng), u(rng));
            break; // far beyond mu F_n: slides
        case 2:
            s = 0.01 * c.normal;
            break; // along the normal: dropped
        case 3:
            s = Vec3(1e-170, 0.0, 0.0);
            break; // |s|^2 underflows to zero
        default:
            break; // a fresh contact
        }
    }
}

} // namespace

/// Both materials of twoMaterials() without rolling resistance: every batch then takes the
/// lanes' path without it.
SpringDashpot twoMaterialsWithoutRolling() {
    MaterialTable<LinearContactParams> table(2);
    SpringDashpot const with = twoMaterials();
    for (std::uint32_t a = 0; a < 2; ++a)
        for (std::uint32_t b = a; b < 2; ++b) {
            LinearContactParams p = with.materials()(a, b);
            p.rollingFriction = 0.0;
            table.set(a, b, p);
        }
    return SpringDashpot{table};
}

/// One material, (0, 0) of twoMaterials(), with or without rolling resistance: the lanes then
/// read the parameters as constants.
SpringDashpot oneMaterial(bool rolling) {
    LinearContactParams p = twoMaterials().materials()(0, 0);
    p.rollingFriction = rolling ? p.rollingFriction : 0.0;
    return SpringDashpot{MaterialTable<LinearContactParams>(1, p)};
}

/// Four passes over a dense random pack, evaluated with evaluatePair and in batches.
void expectSameSharesAndSpringsAsEvaluatePair(SpringDashpot const& model) {
    SCOPED_TRACE(model.hasRollingSpring() ? "model C" : "model A");
    double const dt = 2e-3;
    ParticleStorage one = randomPack(3, 600, 7.0);
    for (std::size_t k = 0; k < one.size(); ++k) // every grain of a known material
        one.setType(k, one.type(k) % static_cast<std::uint32_t>(model.materials().numTypes()));
    WallList walls;
    ContactDetector detector;
    ContactList contacts;
    detector.detect(one, walls, everywhere(), contacts);
    ASSERT_GT(contacts.pairs.size(), 2 * SpringDashpotBatch::kCapacity);
    seedSprings(one, contacts.pairs, model.hasRollingSpring());
    ParticleStorage batched = one;

    SpringDashpotBatch batch;
    for (std::uint32_t stamp = 1; stamp <= 4; ++stamp) {
        detector.detect(one, walls, everywhere(), contacts);
        std::vector<Share> expected, got;
        auto scalarSink = recordInto(expected);
        for (Contact const& c : contacts.pairs) {
            std::uint8_t hint = 0;
            evaluatePair(one, c, model, dt, stamp, hint, scalarSink);
        }
        auto batchSink = recordInto(got);
        BatchedSpringDashpot pairs(batched, model, dt, stamp, batch, batchSink);
        for (Contact const& c : contacts.pairs) {
            std::uint8_t hint = 0;
            pairs(c, hint);
        }
        pairs.finish();

        expectSameShares(got, expected);
        expectSameHistories(batched, one);
        for (ParticleStorage* ps : {&one, &batched})
            for (std::size_t k = 0; k < ps->size(); ++k) {
                ps->position(k) += dt * ps->velocity(k);
                ps->history(k).keepOnly(stamp);
            }
    }
}

TEST(SpringDashpotBatch, SameSharesAndSpringsAsEvaluatePairOverSeveralPasses) {
    expectSameSharesAndSpringsAsEvaluatePair(twoMaterials());
}

TEST(SpringDashpotBatch, SameSharesAndSpringsWithoutRollingResistance) {
    expectSameSharesAndSpringsAsEvaluatePair(twoMaterialsWithoutRolling());
}

TEST(SpringDashpotBatch, SameSharesAndSpringsWithOneMaterial) {
    expectSameSharesAndSpringsAsEvaluatePair(oneMaterial(true));
    expectSameSharesAndSpringsAsEvaluatePair(oneMaterial(false));
}

TEST(SpringDashpotBatch, SameSharesAndSpringsWithModelC) {
    // Rolling springs stored beside the tangential ones, models A and C in one batch, the
    // damping cap, k_r given and by default; one material (constants in the lanes) too.
    SpringDashpot const mixed = twoMaterials(true);
    ASSERT_TRUE(mixed.hasRollingSpring());
    expectSameSharesAndSpringsAsEvaluatePair(mixed);
    LinearContactParams p = mixed.materials()(0, 0);
    expectSameSharesAndSpringsAsEvaluatePair(
        SpringDashpot{MaterialTable<LinearContactParams>(1, p)});
}

class SpringDashpotBatchModels : public ::testing::TestWithParam<bool> {};

TEST_P(SpringDashpotBatchModels, APairMetTwiceInOnePassSeesTheSpringOfItsFirstEvaluation) {
    // The same contact handed over twice (as a pair touching through two periodic images is),
    // with batch-mates before and between: the second evaluation must start from the springs
    // the first one left, as with evaluatePair (model A; model C with its rolling spring).
    SpringDashpot const model = twoMaterials(GetParam());
    ParticleStorage one = randomPack(5, 300, 5.0);
    WallList walls;
    ContactDetector detector;
    ContactList contacts;
    detector.detect(one, walls, everywhere(), contacts);
    ASSERT_GT(contacts.pairs.size(), 10U);
    // A frictional pair (types 0 and 0: its spring changes the force) to repeat.
    std::size_t rep = 0;
    while (one.type(contacts.pairs[rep].i) != 0 || one.type(contacts.pairs[rep].j) != 0)
        ++rep;
    ASSERT_LT(rep, 10U);
    std::vector<Contact> stream(contacts.pairs.begin(), contacts.pairs.begin() + 10);
    stream.push_back(contacts.pairs[rep]);
    stream.push_back(contacts.pairs[rep == 7 ? 8 : 7]);
    stream.push_back(contacts.pairs[rep]);
    ParticleStorage batched = one;

    std::vector<Vec3> expected, got;
    auto scalarSink = [&](std::size_t, Uid, Vec3 const& f, Vec3 const& t) {
        expected.push_back(f);
        expected.push_back(t);
    };
    auto batchSink = [&](std::size_t, Uid, Vec3 const& f, Vec3 const& t) {
        got.push_back(f);
        got.push_back(t);
    };
    SpringDashpotBatch batch;
    BatchedSpringDashpot pairs(batched, model, 1e-2, 1, batch, batchSink);
    for (Contact const& c : stream) {
        std::uint8_t h1 = 0, h2 = 0;
        evaluatePair(one, c, model, 1e-2, 1, h1, scalarSink);
        pairs(c, h2);
    }
    pairs.finish();
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t k = 0; k < got.size(); ++k)
        EXPECT_TRUE(sameBits(got[k], expected[k])) << "share " << k;
    // The repeats changed the force (and model C's couple): the test would see a stale spring.
    EXPECT_FALSE(sameBits(expected[4 * rep], expected[4 * 12]));
    EXPECT_FALSE(sameBits(expected[4 * rep + 1], expected[4 * 12 + 1]));
    Contact const& c = contacts.pairs[rep];
    for (Uid const key : {one.uid(c.j), rollingKey(one.uid(c.j))}) {
        HistoryEntry const* a = one.history(c.i).find(key);
        HistoryEntry const* b = batched.history(c.i).find(key);
        ASSERT_EQ(a == nullptr, !GetParam() && key != one.uid(c.j));
        ASSERT_EQ(b == nullptr, a == nullptr);
        if (a) {
            EXPECT_TRUE(sameBits(a->spring, b->spring));
        }
    }
}

TEST_P(SpringDashpotBatchModels, FreshSpringsOfOneGrainSurviveTheGrowthOfItsHistory) {
    // One grain (the lowest uid, so every contact's history lives on it) touching twelve new
    // partners in one batch: each first touch inserts an entry and may move the block the
    // earlier contacts' entries sit in. Every spring must still land in the history, with the
    // bits evaluatePair leaves (a spring written through a stale pointer would be lost); with
    // model C two entries per contact.
    SpringDashpot const model = twoMaterials(GetParam());
    ParticleStorage one;
    one.add(sphere(makeUid(0, 1), Vec3::Zero(), 0.5, 1.0, Vec3(0.3, -0.2, 0.1)));
    for (std::size_t k = 0; k < 12; ++k) {
        double const phi = 0.5 * static_cast<double>(k), z = -0.8 + 0.15 * static_cast<double>(k);
        double const rho = std::sqrt(1.0 - z * z);
        Vec3 const dir(rho * std::cos(phi), rho * std::sin(phi), z);
        ParticleInit partner = sphere(makeUid(0, 10 + k), 0.95 * dir, 0.5, 1.0,
                                      Vec3(0.1 * static_cast<double>(k), 0.2, -0.3));
        partner.angularVelocity = Vec3(0.5, -0.2 * static_cast<double>(k), 1.0); // rolls
        one.add(partner);
    }
    WallList walls;
    ContactDetector detector;
    ContactList contacts;
    detector.detect(one, walls, everywhere(), contacts);
    ParticleStorage batched = one;
    auto ignore = [](std::size_t, Uid, Vec3 const&, Vec3 const&) {};
    SpringDashpotBatch batch;
    BatchedSpringDashpot pairs(batched, model, 1e-2, 1, batch, ignore);
    for (Contact const& c : contacts.pairs) {
        if (c.i != 0)
            continue; // partners touching each other: not this test's subject
        std::uint8_t h1 = 0, h2 = 0;
        evaluatePair(one, c, model, 1e-2, 1, h1, ignore);
        pairs(c, h2);
    }
    pairs.finish();
    auto const& expected = one.history(0).entries();
    auto const& got = batched.history(0).entries();
    std::size_t const entries = GetParam() ? 24U : 12U;
    ASSERT_EQ(got.size(), entries);
    ASSERT_EQ(expected.size(), entries);
    for (std::size_t e = 0; e < entries; ++e) {
        EXPECT_EQ(got[e].partner, expected[e].partner);
        EXPECT_NE(expected[e].spring.squaredNorm(), 0.0); // the test needs moving springs
        EXPECT_TRUE(sameBits(got[e].spring, expected[e].spring)) << "entry " << e;
    }
}

INSTANTIATE_TEST_SUITE_P(SpringDashpotBatch, SpringDashpotBatchModels, ::testing::Bool(),
                         [](auto const& p) { return p.param ? "ModelC" : "ModelA"; });

TEST(SpringDashpotBatch, KeptHitsAreHandedOverAsOneByOne) {
    // A list's blocks of kept pairs handed over at once (keptHits) and pair by pair: the same
    // shares with the same bits, the same springs and stamps left beside the list, the batch
    // filling in the middle of a block; springs that continue (stamped this pass or the one
    // before) and springs that restart from zero (older, or never touched).
    SpringDashpot const model = oneMaterial(false);
    ParticleStorage ps = randomPack(11, 600, 7.0);
    for (std::size_t k = 0; k < ps.size(); ++k)
        ps.setType(k, 0);
    WallList walls;
    ContactDetector detector;
    ContactList contacts;
    detector.detect(ps, walls, everywhere(), contacts);
    std::size_t const n = contacts.pairs.size();
    ASSERT_GT(n, 4 * SpringDashpotBatch::kCapacity);
    std::uint32_t const stamp = 7;
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<KeptSpring> byOne(n);
    for (std::size_t p = 0; p < n; ++p) {
        byOne[p].spring = Vec3(u(rng), u(rng), u(rng)) * 1e-3;
        std::uint32_t const stamps[] = {stamp, stamp - 1, stamp - 2, KeptSpring::kUntouched};
        byOne[p].stamp = stamps[p % 4];
    }
    std::vector<KeptSpring> atOnce = byOne;
    std::vector<Share> expected, got;
    auto oneSink = recordInto(expected);
    auto allSink = recordInto(got);
    SpringDashpotBatch oneBatch, allBatch;
    BatchedSpringDashpot one(ps, model, 1e-2, stamp, oneBatch, oneSink);
    BatchedSpringDashpot all(ps, model, 1e-2, stamp, allBatch, allSink);
    std::size_t handed = 0;
    for (std::size_t first = 0; first + 64 <= n; first += 64) {
        std::array<std::uint32_t, 64> i{}, j{}, at{};
        std::uint64_t hits = 0;
        for (std::size_t t = 0; t < 64; ++t) {
            Contact const& c = contacts.pairs[first + t];
            i[t] = static_cast<std::uint32_t>(c.i);
            j[t] = static_cast<std::uint32_t>(c.j);
            at[t] = static_cast<std::uint32_t>(first + 63 - t); // any slots, in any order
            hits |= std::uint64_t{u(rng) < 0.4 ? 1U : 0U} << t;
        }
        for (std::uint64_t h = hits; h != 0; h &= h - 1) {
            auto const t = static_cast<std::size_t>(std::countr_zero(h));
            one(PairOverlap{i[t], j[t], Vec3::Zero()}, byOne[at[t]]);
            ++handed;
        }
        all.keptHits(i.data(), j.data(), at.data(), hits, atOnce.data());
    }
    one.finish();
    all.finish();
    ASSERT_GT(handed, 2 * SpringDashpotBatch::kCapacity);
    ASSERT_EQ(expected.size(), 2 * handed);
    expectSameShares(got, expected);
    std::size_t restarted = 0;
    for (std::size_t p = 0; p < n; ++p) {
        EXPECT_EQ(atOnce[p].stamp, byOne[p].stamp) << "pair " << p;
        EXPECT_TRUE(sameBits(atOnce[p].spring, byOne[p].spring)) << "pair " << p;
        restarted += byOne[p].stamp == stamp && p % 4 >= 2 ? 1 : 0;
    }
    EXPECT_GT(restarted, 0U); // springs that restarted from zero were handed over
}

TEST(SpringDashpotBatch, AddKeptHitsStopsWhenFullAndReturnsTheRest) {
    ParticleStorage ps = randomPack(17, 40, 3.0);
    std::vector<KeptSpring> springs(80);
    SpringDashpotBatch batch;
    for (std::size_t k = 0; k + 4 < SpringDashpotBatch::kCapacity; ++k)
        batch.addKept(0, 1, Vec3::Zero(), springs[k], 1);
    std::array<std::uint32_t, 64> i{}, j{}, at{};
    for (std::uint32_t t = 0; t < 64; ++t) {
        i[t] = t % 20;
        j[t] = 20 + t % 20;
        at[t] = 10 + t;
    }
    std::uint64_t const hits = 0b1011'0110'1000ULL; // bits 3, 5, 6, 8, 9, 11
    std::uint64_t const rest =
        batch.addKeptHits(i.data(), j.data(), at.data(), hits, springs.data(), 1);
    EXPECT_EQ(rest, 0b1010'0000'0000ULL); // four added, 9 and 11 left
    ASSERT_TRUE(batch.full());
    std::size_t const added[] = {3, 5, 6, 8};
    for (std::size_t a = 0; a < 4; ++a) {
        std::size_t const k = SpringDashpotBatch::kCapacity - 4 + a;
        EXPECT_EQ(batch.i(k), i[added[a]]);
        EXPECT_EQ(batch.j(k), j[added[a]]);
        EXPECT_EQ(batch.kept(k), &springs[at[added[a]]]);
    }
}
