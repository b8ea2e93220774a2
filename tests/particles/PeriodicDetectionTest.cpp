// Contact detection with periodic image copies: each contact is emitted exactly once over the
// blocks tiling a periodic domain (and over the image copies inside one block), with the same
// bits whatever the tiling; the swallowed-centre and wall rules.
#include "domain/BlockId.hpp"
#include "domain/ForestGeometry.hpp"
#include "particles/detection/ContactDetector.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "tests/particles/ParticleTestUtil.hpp"
#include "tests/particles/PeriodicTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <tuple>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;
using regolith::core::AABB;

namespace {

using PairKey = std::tuple<Uid, Uid, CopyImage>; ///< uid_i < uid_j, image(j) - image(i)

/// Every contact emitted by any block of a tiling, keyed by uids and image difference.
struct Emitted {
    std::map<PairKey, std::vector<Contact>> pairs;
    std::map<std::pair<Uid, std::size_t>, std::vector<WallContact>> walls;
    std::size_t copies = 0;
    std::vector<std::size_t> pairsPerBlock;
};

Emitted detectAll(std::vector<ParticleInit> const& bodies, Tiling const& tiling,
                  WallList const& walls = {}, DetectorConfig config = {}) {
    Emitted out;
    ContactDetector detector(config);
    for (AABB const& box : tiling.boxes) {
        ParticleStorage const ps = blockCopies(bodies, box, tiling.frame);
        out.copies += ps.size();
        ContactList found;
        detector.detect(ps, walls, box, tiling.frame, found);
        out.pairsPerBlock.push_back(found.pairs.size());
        for (Contact const& c : found.pairs) {
            EXPECT_LT(ps.uid(c.i), ps.uid(c.j)) << "canonical order";
            EXPECT_TRUE(sameBits(c.shiftJ, imageOffset(subtractImages(ps.image(c.j), ps.image(c.i)),
                                                       tiling.frame.period())));
            out.pairs[{ps.uid(c.i), ps.uid(c.j), subtractImages(ps.image(c.j), ps.image(c.i))}]
                .push_back(c);
        }
        for (WallContact const& c : found.walls) {
            EXPECT_TRUE(ps.flags(c.particle).isMaster()) << "a shadow evaluated a wall contact";
            EXPECT_TRUE(isZero(ps.image(c.particle)));
            out.walls[{ps.uid(c.particle), c.wall}].push_back(c);
        }
        if (config.sortByUid) {
            auto key = [&ps](Contact const& c) {
                return std::tuple(ps.uid(c.i), ps.uid(c.j),
                                  subtractImages(ps.image(c.j), ps.image(c.i)));
            };
            EXPECT_TRUE(std::is_sorted(
                found.pairs.begin(), found.pairs.end(),
                [&](Contact const& a, Contact const& b) { return key(a) < key(b); }));
        }
    }
    return out;
}

/// Brute force over all pairs and image differences, with the documented canonical geometry
/// written out here: shift = dk * period, d = (x_j + shift) - x_i, overlap iff |d| < r_i + r_j.
std::map<PairKey, double> bruteForcePenetrations(std::vector<ParticleInit> const& bodies,
                                                 PeriodicFrame const& frame) {
    std::map<PairKey, double> out;
    Vec3 const period = frame.period();
    for (ParticleInit const& a : bodies)
        for (ParticleInit const& b : bodies) {
            if (!(a.uid < b.uid) || (a.flags.isFixed() && b.flags.isFixed()))
                continue;
            for (CopyImage const& dk : images(frame)) {
                Vec3 const shift(dk[0] * period[0], dk[1] * period[1], dk[2] * period[2]);
                double const dist = ((b.position + shift) - a.position).norm();
                if (dist < a.radius + b.radius)
                    out[{a.uid, b.uid, dk}] = a.radius + b.radius - dist;
            }
        }
    return out;
}

AABB const kDomain{Vec3::Zero(), Vec3::Constant(10.0)};

} // namespace

TEST(PeriodicFrame, WrapsLikeTheForestAndIsTheIdentityByDefault) {
    PeriodicFrame const none;
    EXPECT_FALSE(none.anyPeriodic());
    EXPECT_EQ(none.period(), Vec3::Zero());
    auto const [w0, o0] = none.wrap(Vec3(-1e300, 5, 1e300));
    EXPECT_EQ(w0, Vec3(-1e300, 5, 1e300));
    EXPECT_EQ(o0, kNoImage);

    regolith::domain::ForestGeometry const g(AABB{Vec3(-1, 0, 0), Vec3(2.5, 3, 7)}, {2, 1, 1},
                                             {true, false, true}, 0);
    PeriodicFrame const frame(g);
    EXPECT_EQ(frame.period(), Vec3(3.5, 0, 7));
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-12.0, 15.0);
    std::vector<Vec3> points{Vec3(-1, 1, 0), Vec3(2.5, 1, 7), Vec3(-1 - 1e-17, 1, -1e-300),
                             Vec3(std::nextafter(2.5, 0.0), -4, std::nextafter(7.0, 8.0)),
                             Vec3(6.0, 1, 14.0)};
    for (int n = 0; n < 2000; ++n)
        points.emplace_back(u(rng), u(rng), u(rng));
    for (Vec3 const& p : points) {
        auto const [w, o] = frame.wrap(p);
        Vec3 const forestWrap = g.wrap(p);
        Vec3 q = p;
        q.y() = 1.0; // locate refuses points outside on the non-periodic axis
        auto const location = g.locate(q);
        ASSERT_TRUE(location.has_value());
        EXPECT_TRUE(sameBits(w, forestWrap));
        EXPECT_EQ(o[0], location->image[0]);
        EXPECT_EQ(o[1], 0);
        EXPECT_EQ(o[2], location->image[2]);
        EXPECT_GE(w.x(), -1.0);
        EXPECT_LT(w.x(), 2.5);
        EXPECT_GE(w.z(), 0.0);
        EXPECT_LT(w.z(), 7.0);
        EXPECT_EQ(w.y(), p.y());
        EXPECT_NEAR(w.x() + o[0] * 3.5, p.x(), 1e-13);
        EXPECT_NEAR(w.z() + o[2] * 7.0, p.z(), 1e-13);
    }
    EXPECT_THROW((void)frame.wrap(Vec3(std::nan(""), 0, 0)), regolith::core::Error);
    EXPECT_THROW((void)frame.wrap(Vec3(0, 0, 1000.0)), regolith::core::Error); // > 7 periods
}

TEST(PeriodicDetection, ContactThroughThePeriodicFaceIsFoundOnceInOneBlockAndInTwo) {
    // Periodic in x only. A at x = 0.25 and B near the high face touch through x = 0. In one
    // block that is its own periodic neighbour, both masters plus their image copies (A at
    // +1, B at -1, shadows) hold the pair twice: (A, B-1) and (A+1, B), the same canonical
    // contact. Case 1: B at 9.75, the contact point is exactly on the face x = 0 (image 0, so
    // the instance with image(A) = 0 evaluates). Case 2: B at 9.5, the point is at x = -0.125
    // (image -1, so the instance with image(A) = +1).
    PeriodicFrame const frame(kDomain, {true, false, false});
    struct Case {
        double xB, penetration, pointX;
        int imageOfA;
    };
    for (Case const& k : {Case{9.75, 0.5, 0.0, 0}, Case{9.5, 0.25, -0.125, 1}}) {
        SCOPED_TRACE(::testing::Message() << "B at " << k.xB);
        std::vector<ParticleInit> const bodies{sphere(3, Vec3(0.25, 5, 5), 0.5, 1.0),
                                               sphere(8, Vec3(k.xB, 5, 5), 0.5, 1.0)};
        ParticleStorage one;
        for (ParticleInit const& p : bodies)
            one.add(p);
        ParticleInit a = bodies[0], b = bodies[1];
        a.image = {1, 0, 0};
        b.image = {-1, 0, 0};
        a.flags = b.flags = Flag::Shadow;
        one.add(a);
        one.add(b);
        ContactDetector detector;
        ContactList found;
        detector.detect(one, WallList{}, kDomain, frame, found);
        EXPECT_EQ(detector.stats().overlapsFound, 2U); // both instances overlap
        ASSERT_EQ(found.pairs.size(), 1U);
        Contact const c = found.pairs[0];
        EXPECT_EQ(one.uid(c.i), 3U);
        EXPECT_EQ(one.uid(c.j), 8U);
        EXPECT_EQ(one.image(c.i)[0], k.imageOfA);
        EXPECT_EQ(one.image(c.j)[0], k.imageOfA - 1);
        // All values are dyadic: exact.
        EXPECT_EQ(c.shiftJ, Vec3(-10, 0, 0));
        EXPECT_EQ(c.normal, Vec3(-1, 0, 0));
        EXPECT_EQ(c.penetration, k.penetration);
        EXPECT_EQ(c.point, Vec3(k.pointX, 5, 5));

        // Two blocks [0, 5) and [5, 10): each holds the copies it overlaps; the union of what
        // they emit is the one-block contact, once and bit for bit.
        Emitted const two = detectAll(bodies, tile(kDomain, {true, false, false}, {2, 1, 1}));
        ASSERT_EQ(two.pairs.size(), 1U);
        auto const& [key, list] = *two.pairs.begin();
        EXPECT_EQ(key, PairKey(3, 8, CopyImage{-1, 0, 0}));
        ASSERT_EQ(list.size(), 1U);
        EXPECT_TRUE(sameBits(list[0], c));
        EXPECT_EQ(two.copies, 4U);
        // Case 1 is evaluated by the lower block, case 2 by the upper one.
        EXPECT_EQ(two.pairsPerBlock,
                  (std::vector<std::size_t>{k.imageOfA == 0 ? 1U : 0U, k.imageOfA == 0 ? 0U : 1U}));
    }
}

TEST(PeriodicDetection, RandomSpheresEveryContactOnceWithTheSameBitsForAnyTiling) {
    // Polydisperse spheres (radii 0.15 - 1 and four of radius 2, so the large pass runs, some
    // Fixed) in [0, 10)^3, some placed on or next to the faces, fully periodic and periodic in
    // x and y only; tilings of 1 to 3 blocks per axis. The multiset of emitted contacts over
    // all blocks must equal the brute-force list over all image differences, each once, and
    // the contact bits must not depend on the tiling.
    std::mt19937_64 rng(20240611);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<ParticleInit> bodies;
    std::vector<Uid> uids(340);
    for (std::size_t k = 0; k < uids.size(); ++k)
        uids[k] = makeUid(static_cast<int>(k % 4), 7 * k);
    std::shuffle(uids.begin(), uids.end(), rng);
    for (std::size_t k = 0; k < uids.size(); ++k) {
        double const r = k < 4 ? 2.0 : 0.15 * std::pow(1.0 / 0.15, u(rng));
        Vec3 x = 10.0 * Vec3(u(rng), u(rng), u(rng));
        if (k % 17 == 0) // on a face, or just below the high face
            x[static_cast<Eigen::Index>(k % 3)] = k % 2 == 0 ? 0.0 : std::nextafter(10.0, 0.0);
        ParticleInit p = sphere(uids[k], x, r, 1.0);
        if (u(rng) < 0.1)
            p.flags = Flag::Fixed;
        bodies.push_back(p);
    }

    std::size_t crossing = 0;
    for (std::array<bool, 3> const periodic :
         {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, true, false}}) {
        SCOPED_TRACE(::testing::Message() << "periodic z " << periodic[2]);
        PeriodicFrame const frame(kDomain, periodic);
        auto const reference = bruteForcePenetrations(bodies, frame);
        EXPECT_GT(reference.size(), 300U);
        Emitted first;
        std::array<std::array<int, 3>, 5> const tilings{
            {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {1, 2, 3}, {3, 2, 1}}};
        for (std::size_t t = 0; t < tilings.size(); ++t) {
            SCOPED_TRACE(::testing::Message() << "tiling " << t);
            DetectorConfig config;
            config.sortByUid = t == 2;
            if (t == 3)
                config.largeRadius = 0.5; // many large spheres: the sweep on local positions
            Emitted const e = detectAll(bodies, tile(kDomain, periodic, tilings[t]), {}, config);
            EXPECT_EQ(e.pairs.size(), reference.size());
            for (auto const& [key, list] : e.pairs) {
                EXPECT_EQ(list.size(), 1U) << "pair emitted " << list.size() << " times";
                auto const it = reference.find(key);
                if (it == reference.end()) {
                    ADD_FAILURE() << "not a contact: " << std::get<0>(key) << ","
                                  << std::get<1>(key);
                    continue;
                }
                EXPECT_TRUE(sameBits(list[0].penetration, it->second));
                if (t == 0) {
                    crossing += isZero(std::get<2>(key)) ? 0 : 1;
                } else if (auto const f = first.pairs.find(key); f != first.pairs.end()) {
                    EXPECT_TRUE(sameBits(list[0], f->second[0]));
                }
            }
            for (auto const& [key, pen] : reference)
                EXPECT_TRUE(e.pairs.contains(key))
                    << "missed " << std::get<0>(key) << "," << std::get<1>(key);
            if (t == 0)
                first = e;
        }
    }
    EXPECT_GT(crossing, 20U) << "contacts through periodic faces are exercised";
}

TEST(PeriodicDetection, SwallowedCentreIsEvaluatedOnceByTheBlockOfTheSmallCentre) {
    // A radius-2 sphere swallows the centre of a radius-0.3 one (distance < 2 - 0.3): the
    // contact point lies beyond the small sphere, in another block than its centre. The small
    // centre decides, in both uid orders; case 2 has the point across the periodic face.
    struct Case {
        double bigX, smallX;
        bool periodic;
        std::size_t ownerBlock; ///< the block of the small centre
    };
    for (Case const& k : {Case{4.0, 4.9, false, 0}, Case{9.0, 9.9, true, 1}}) {
        for (bool bigFirst : {true, false}) {
            SCOPED_TRACE(::testing::Message()
                         << "big at " << k.bigX << ", big uid lower " << bigFirst);
            std::vector<ParticleInit> const bodies{
                sphere(bigFirst ? 1 : 2, Vec3(k.bigX, 5, 5), 2.0, 10.0),
                sphere(bigFirst ? 2 : 1, Vec3(k.smallX, 5.1, 5), 0.3, 1.0)};
            std::array<bool, 3> const periodic{k.periodic, false, false};
            Tiling const tiling = tile(kDomain, periodic, {2, 1, 1});
            Emitted const e = detectAll(bodies, tiling);
            ASSERT_EQ(e.pairs.size(), 1U);
            auto const& list = e.pairs.begin()->second;
            ASSERT_EQ(list.size(), 1U);
            EXPECT_EQ(e.pairsPerBlock[k.ownerBlock], 1U);
            // The contact point itself lies (after wrapping) in the other block.
            auto const [w, o] = tiling.frame.wrap(list[0].point);
            EXPECT_FALSE(tiling.boxes[k.ownerBlock].contains(w));
            EXPECT_GT(list[0].penetration, 1.3);
            // One block covering the domain agrees bit for bit.
            Emitted const one = detectAll(bodies, tile(kDomain, periodic, {1, 1, 1}));
            ASSERT_EQ(one.pairs.size(), 1U);
            ASSERT_EQ(one.pairs.begin()->second.size(), 1U);
            EXPECT_TRUE(sameBits(one.pairs.begin()->second[0], list[0]));
        }
    }
}

TEST(PeriodicDetection, DeepOverlapAtAnOpenFaceIsEvaluatedOnce) {
    // A radius-0.5 grain 0.3 from the open face x = 0, a radius-3 one overlapping it by more
    // than the small diameter but less than 2 diameters: the contact point lies behind the
    // small centre, outside the domain (x = -0.1 and -0.15 below), so while it decided, no block
    // evaluated the pair. The small centre decides, on one block and on two.
    for (double bigX : {2.0, 1.9}) {
        for (bool bigFirst : {true, false}) {
            SCOPED_TRACE(::testing::Message()
                         << "big at " << bigX << ", big uid lower " << bigFirst);
            std::vector<ParticleInit> const bodies{
                sphere(bigFirst ? 1 : 2, Vec3(bigX, 5, 5), 3.0, 10.0),
                sphere(bigFirst ? 2 : 1, Vec3(0.3, 5, 5), 0.5, 1.0)};
            for (int blocks : {1, 2}) {
                Tiling const tiling = tile(kDomain, {false, false, false}, {blocks, 1, 1});
                Emitted const e = detectAll(bodies, tiling);
                ASSERT_EQ(e.pairs.size(), 1U) << blocks << " blocks";
                auto const& list = e.pairs.begin()->second;
                ASSERT_EQ(list.size(), 1U);
                EXPECT_EQ(e.pairsPerBlock[0], 1U); // the block of the small centre
                EXPECT_LT(list[0].point.x(), 0.0); // the contact point left the domain
                EXPECT_GT(list[0].penetration, 1.0);
            }
        }
    }
}

TEST(PeriodicDetection, WallOnTheDomainFaceIsEvaluatedOnceByTheMaster) {
    // Periodic in x and y, a wall on the face z = 0. Sphere 7 sits at a periodic edge (copies in
    // several blocks and at several images), sphere 9 in the middle of the domain; both
    // penetrate the wall, sphere 11 does not. The contact point is behind the wall, outside
    // every block; the master alone evaluates.
    std::vector<ParticleInit> const bodies{sphere(7, Vec3(9.9, 0.05, 0.3), 0.5, 1.0),
                                           sphere(9, Vec3(5.0, 5.0, 0.45), 0.5, 1.0),
                                           sphere(11, Vec3(2.0, 2.0, 0.6), 0.5, 1.0)};
    WallList walls;
    walls.add(Vec3(0, 0, 0), Vec3::UnitZ());
    for (std::array<int, 3> const n :
         {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{2, 2, 2}, std::array<int, 3>{2, 3, 1}}) {
        Emitted const e = detectAll(bodies, tile(kDomain, {true, true, false}, n), walls);
        EXPECT_GE(e.copies, 3U + 3U); // sphere 7 has at least three more copies
        ASSERT_EQ(e.walls.size(), 2U);
        for (auto const& [key, list] : e.walls) {
            EXPECT_EQ(list.size(), 1U);
            EXPECT_TRUE(key.first == 7 || key.first == 9);
        }
        WallContact const& c = e.walls.at({7, 0})[0];
        EXPECT_NEAR(c.penetration, 0.2, 1e-15);
        EXPECT_NEAR((c.point - Vec3(9.9, 0.05, -0.1)).norm(), 0.0, 1e-15);
    }
}

TEST(PeriodicDetection, RefusesAnImageOnANonPeriodicAxis) {
    ParticleStorage ps;
    ParticleInit p = sphere(1, Vec3(1, 1, 1), 0.5, 1.0);
    p.image = {0, 0, 1};
    p.flags = Flag::Shadow;
    ps.add(p);
    ContactDetector detector;
    ContactList found;
    EXPECT_THROW(detector.detect(ps, WallList{}, kDomain,
                                 PeriodicFrame(kDomain, {true, true, false}), found),
                 regolith::core::Error);
}
