// Reproducible force summation: evaluateContactsRecorded + sumRecords against the direct
// accumulation of evaluateContacts, independence of the contact order and of which storage
// evaluated which contact, and bitwise agreement of the per-contact shares (torques with
// shiftJ lever arms) across block tilings of a periodic domain.
#include "particles/detection/ContactDetector.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "tests/particles/ParticleTestUtil.hpp"
#include "tests/particles/PeriodicTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <tuple>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;

namespace {

SpringDashpot frictionalModel(bool rolling = true) {
    LinearContactParams p;
    p.stiffness = 2000.0;
    p.tangentialStiffness = 600.0;
    p.restitution = 0.7;
    p.friction = 0.5;
    p.rollingFriction = rolling ? 0.05 : 0.0;
    return SpringDashpot{MaterialTable<LinearContactParams>(1, p)};
}

/// A dense random pack with random translational and angular velocities, resting on a wall.
std::vector<ParticleInit> randomBodies(std::uint64_t seed, std::size_t n, double box) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<ParticleInit> out;
    for (std::size_t k = 0; k < n; ++k) {
        double const r = 0.35 + 0.3 * u(rng);
        ParticleInit p =
            sphere(makeUid(static_cast<int>(k % 5), 3 * k + 1), box * Vec3(u(rng), u(rng), u(rng)),
                   r, 1.0 + u(rng), Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
        p.angularVelocity = 4.0 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        out.push_back(p);
    }
    return out;
}

/// The storage of `bodies` after one evaluation pass with stamp 1 (springs non-zero), forces
/// reset.
ParticleStorage withHistory(std::vector<ParticleInit> const& bodies, WallList& walls,
                            SpringDashpot const& model) {
    ParticleStorage ps;
    for (ParticleInit const& b : bodies)
        ps.add(b);
    ContactDetector detector;
    ContactList contacts;
    detector.detect(ps, walls, everywhere(), contacts);
    evaluateContacts(ps, walls, contacts, model, 1e-3, 1);
    for (std::size_t k = 0; k < ps.size(); ++k)
        ps.position(k) += 1e-3 * ps.velocity(k); // so the second pass sees a new geometry
    ps.resetForces();
    walls.resetForces();
    return ps;
}

void expectSameForces(ParticleStorage const& a, ParticleStorage const& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
        std::size_t const m = b.find(a.uid(k), a.image(k));
        ASSERT_NE(m, ParticleStorage::kNotFound);
        EXPECT_TRUE(sameBits(a.force(k), b.force(m))) << "uid " << a.uid(k);
        EXPECT_TRUE(sameBits(a.torque(k), b.torque(m))) << "uid " << a.uid(k);
    }
}

} // namespace

TEST(RecordedEvaluation, SumOfRecordsMatchesDirectAccumulation) {
    SpringDashpot const model = frictionalModel();
    WallList walls;
    walls.add(Vec3(0, 0, 0.2), Vec3::UnitZ());
    auto const bodies = randomBodies(1, 500, 8.0);
    ParticleStorage const start = withHistory(bodies, walls, model);
    ContactDetector detector;
    ContactList contacts;
    detector.detect(start, walls, everywhere(), contacts);
    ASSERT_GT(contacts.pairs.size(), 300U);
    ASSERT_GT(contacts.walls.size(), 5U);

    ParticleStorage direct = start;
    WallList directWalls = walls;
    evaluateContacts(direct, directWalls, contacts, model, 1e-3, 2);

    ParticleStorage recorded = start;
    WallList recordedWalls = walls;
    std::vector<ForceRecord> records;
    evaluateContactsRecorded(recorded, recordedWalls, contacts, model, 1e-3, 2, records);
    EXPECT_EQ(records.size(), 2 * contacts.pairs.size() + contacts.walls.size());
    for (std::size_t k = 0; k < recorded.size(); ++k) { // nothing was added in place
        EXPECT_EQ(recorded.force(k), Vec3::Zero());
        EXPECT_EQ(recorded.torque(k), Vec3::Zero());
    }
    // Everything else the plain evaluation does happened the same way.
    for (std::size_t k = 0; k < recorded.size(); ++k) {
        auto const& h = recorded.history(k).entries();
        auto const& g = direct.history(k).entries();
        ASSERT_EQ(h.size(), g.size());
        for (std::size_t e = 0; e < h.size(); ++e) {
            EXPECT_EQ(h[e].partner, g[e].partner);
            EXPECT_EQ(h[e].stamp, g[e].stamp);
            EXPECT_TRUE(sameBits(h[e].spring, g[e].spring));
        }
    }
    EXPECT_TRUE(sameBits(recordedWalls.force(0), directWalls.force(0)));

    // Sum of magnitudes per copy: the scale of the summation round-off.
    std::vector<double> scaleF(recorded.size(), 0.0), scaleT(recorded.size(), 0.0);
    for (ForceRecord const& r : records) {
        scaleF[r.copy] += r.force.norm();
        scaleT[r.copy] += r.torque.norm();
    }
    sumRecords(records, recorded);
    EXPECT_TRUE(std::is_sorted(
        records.begin(), records.end(),
        [&](ForceRecord const& a, ForceRecord const& b) { return recordOrder(recorded, a, b); }));
    double worst = 0.0;
    for (std::size_t k = 0; k < recorded.size(); ++k) {
        EXPECT_LE((recorded.force(k) - direct.force(k)).norm(), 1e-14 * scaleF[k]);
        EXPECT_LE((recorded.torque(k) - direct.torque(k)).norm(), 1e-14 * scaleT[k]);
        if (scaleF[k] > 0.0)
            worst = std::max(worst, (recorded.force(k) - direct.force(k)).norm() / scaleF[k]);
    }
    // Each copy's total is summed from zero in ascending partner uid.
    std::size_t const k = contacts.pairs[0].i;
    Vec3 sum = Vec3::Zero();
    Uid last = 0;
    for (ForceRecord const& r : records)
        if (r.copy == k) {
            EXPECT_GE(r.partner, last);
            last = r.partner;
            sum += r.force;
        }
    EXPECT_TRUE(sameBits(sum, recorded.force(k)));
    RecordProperty("worst_relative_difference", std::to_string(worst));
}

TEST(RecordedEvaluation, SumDoesNotDependOnContactOrderOrOnWhichStorageEvaluated) {
    SpringDashpot const model = frictionalModel();
    WallList walls;
    walls.add(Vec3(0, 0, 0.2), Vec3::UnitZ());
    auto const bodies = randomBodies(2, 400, 7.0);
    ParticleStorage const start = withHistory(bodies, walls, model);
    ContactDetector detector;
    ContactList contacts;
    detector.detect(start, walls, everywhere(), contacts);

    ParticleStorage reference = start;
    {
        WallList w = walls;
        std::vector<ForceRecord> records;
        evaluateContactsRecorded(reference, w, contacts, model, 1e-3, 2, records);
        sumRecords(records, reference);
    }
    std::mt19937_64 rng(9);
    // The same contacts in a shuffled order.
    {
        ContactList shuffled = contacts;
        std::shuffle(shuffled.pairs.begin(), shuffled.pairs.end(), rng);
        std::shuffle(shuffled.walls.begin(), shuffled.walls.end(), rng);
        ParticleStorage ps = start;
        WallList w = walls;
        std::vector<ForceRecord> records;
        evaluateContactsRecorded(ps, w, shuffled, model, 1e-3, 2, records);
        std::shuffle(records.begin(), records.end(), rng);
        sumRecords(records, ps);
        expectSameForces(reference, ps);
    }
    // Split between two storages holding the same particles in different orders (as two
    // blocks, one holding masters and one shadows): each evaluates the contacts a coin flip
    // gives it; the second one's records are mapped to the first by uid and appended first.
    ParticleStorage first = start;
    ParticleStorage second = start;
    std::vector<std::size_t> order(second.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::shuffle(order.begin(), order.end(), rng);
    second.permute(order);
    ContactList secondContacts;
    detector.detect(second, walls, everywhere(), secondContacts);
    auto coin = [](Uid a, Uid b) { return ((a * 2654435761U) ^ (b * 40503U)) % 2 == 0; };
    ContactList mine, theirs;
    for (Contact const& c : contacts.pairs)
        if (coin(first.uid(c.i), first.uid(c.j)))
            mine.pairs.push_back(c);
    for (Contact const& c : secondContacts.pairs)
        if (!coin(second.uid(c.i), second.uid(c.j)))
            theirs.pairs.push_back(c);
    for (WallContact const& c : contacts.walls)
        if (coin(first.uid(c.particle), 0))
            mine.walls.push_back(c);
    for (WallContact const& c : secondContacts.walls)
        if (!coin(second.uid(c.particle), 0))
            theirs.walls.push_back(c);
    EXPECT_EQ(mine.size() + theirs.size(), contacts.size());
    EXPECT_GT(mine.size(), contacts.size() / 4);
    EXPECT_GT(theirs.size(), contacts.size() / 4);
    WallList w1 = walls, w2 = walls;
    std::vector<ForceRecord> records, secondRecords;
    evaluateContactsRecorded(first, w1, mine, model, 1e-3, 2, records);
    evaluateContactsRecorded(second, w2, theirs, model, 1e-3, 2, secondRecords);
    std::vector<ForceRecord> merged;
    merged.reserve(records.size() + secondRecords.size());
    for (ForceRecord r : secondRecords) {
        r.copy = first.find(second.uid(r.copy), second.image(r.copy));
        merged.push_back(r);
    }
    merged.insert(merged.end(), records.begin(), records.end());
    sumRecords(merged, first);
    expectSameForces(reference, first);
}

TEST(RecordedEvaluation, PartnerOrderIsATotalOrderEvenForARepeatedPartner) {
    // A pair touching through two periodic images gives one copy two records with the same
    // partner: they are ordered by their values, so the sum does not depend on arrival order.
    ForceRecord const a{0, 5, Vec3(1, 0, 0), Vec3::Zero()};
    ForceRecord const b{0, 5, Vec3(-0.0, 2, 0), Vec3::Zero()};
    ForceRecord const c{0, 5, Vec3(0.0, 2, 0), Vec3::Zero()};
    ForceRecord const d{0, 4, Vec3(9, 9, 9), Vec3::Zero()};
    EXPECT_TRUE(partnerOrder(d, a));
    EXPECT_TRUE(partnerOrder(b, c)); // -0 before +0: a total order on the bits
    EXPECT_TRUE(partnerOrder(c, a));
    EXPECT_FALSE(partnerOrder(a, c));
    EXPECT_FALSE(partnerOrder(a, a));
    ParticleStorage ps;
    ps.add(sphere(1, Vec3::Zero(), 0.5, 1.0));
    std::vector<ForceRecord> x{a, b, c, d}, y{c, d, a, b};
    sumRecords(x, ps);
    Vec3 const f = ps.force(0);
    ps.resetForces();
    sumRecords(y, ps);
    EXPECT_TRUE(sameBits(ps.force(0), f));
}

TEST(RecordedEvaluation, SharesAreBitwiseTheSameForAnyTilingOfAPeriodicDomain) {
    // Every block of a tiling evaluates its contacts with records; gathered by (target uid,
    // partner uid) the shares -- force and torque, whose lever arm uses shiftJ for j -- are
    // the same bits for one block holding all images and for 2 x 2 x 2 or 3 x 1 x 2 blocks (so a
    // master's total summed in partner order is too). Without rolling resistance a share's
    // torque is lever x force with |lever| < r: the lever arm of j is taken at j's image.
    SpringDashpot const model = frictionalModel(false);
    AABB const domain{Vec3::Zero(), Vec3(6, 6, 6)};
    std::array<bool, 3> const periodic{true, true, true};
    auto const bodies = randomBodies(4, 160, 6.0);
    using Share = std::tuple<Uid, Uid, double, double, double, double, double, double>;
    std::vector<std::vector<Share>> byTiling;
    for (std::array<int, 3> const n :
         {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{2, 2, 2}, std::array<int, 3>{3, 1, 2}}) {
        Tiling const tiling = tile(domain, periodic, n);
        std::vector<Share> shares;
        std::size_t crossing = 0;
        for (AABB const& box : tiling.boxes) {
            ParticleStorage ps = blockCopies(bodies, box, tiling.frame);
            ContactDetector detector;
            ContactList contacts;
            WallList walls;
            detector.detect(ps, walls, box, tiling.frame, contacts);
            for (Contact const& c : contacts.pairs)
                crossing += c.shiftJ.isZero(0.0) ? 0 : 1;
            std::vector<ForceRecord> records;
            evaluateContactsRecorded(ps, walls, contacts, model, 1e-3, 1, records);
            for (ForceRecord const& r : records) {
                EXPECT_LE(r.torque.norm(), ps.radius(r.copy) * r.force.norm() * (1.0 + 1e-12));
                shares.emplace_back(ps.uid(r.copy), r.partner, r.force.x(), r.force.y(),
                                    r.force.z(), r.torque.x(), r.torque.y(), r.torque.z());
            }
        }
        EXPECT_GT(crossing, 10U);
        std::sort(shares.begin(), shares.end());
        byTiling.push_back(shares);
    }
    ASSERT_GT(byTiling[0].size(), 200U);
    for (std::size_t t = 1; t < byTiling.size(); ++t) {
        ASSERT_EQ(byTiling[t].size(), byTiling[0].size());
        for (std::size_t s = 0; s < byTiling[0].size(); ++s) {
            auto const& [u0, p0, f0, f1, f2, t0, t1, t2] = byTiling[0][s];
            auto const& [u1, p1, g0, g1, g2, s0, s1, s2] = byTiling[t][s];
            EXPECT_EQ(u0, u1);
            EXPECT_EQ(p0, p1);
            EXPECT_TRUE(sameBits(Vec3(f0, f1, f2), Vec3(g0, g1, g2)));
            EXPECT_TRUE(sameBits(Vec3(t0, t1, t2), Vec3(s0, s1, s2)));
        }
    }
}
