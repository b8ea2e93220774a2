// Contact detection against an O(N^2) reference, the large-sphere pass, and the rule that
// exactly one block evaluates a contact (without periodic images; PeriodicDetectionTest.cpp
// has those).
#include "particles/detection/ContactDetector.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;
using regolith::core::AABB;

namespace {

using PairKey = std::pair<Uid, Uid>;

/// A reference pair contact and the point that decides which block evaluates it.
struct OwnedContact {
    Contact contact;
    Vec3 owner;
};

/// Brute force: every pair i < j by index, the same geometric definitions as the detector's
/// documentation (written out independently here), kept if the ownership point -- the contact
/// point, or the smaller sphere's centre if the contact point does not lie strictly between
/// the two centres -- is in `region`.
std::map<PairKey, OwnedContact> bruteForcePairs(ParticleStorage const& ps, AABB const& region) {
    std::map<PairKey, OwnedContact> out;
    for (std::size_t a = 0; a < ps.size(); ++a)
        for (std::size_t b = a + 1; b < ps.size(); ++b) {
            if (ps.flags(a).isFixed() && ps.flags(b).isFixed())
                continue;
            std::size_t const i = ps.uid(a) < ps.uid(b) ? a : b, j = i == a ? b : a;
            Vec3 const d = ps.position(j) - ps.position(i);
            double const delta = ps.radius(i) + ps.radius(j) - d.norm();
            if (!(delta > 0.0))
                continue;
            Vec3 const n = d.normalized();
            Vec3 const p = ps.position(i) + (ps.radius(i) - delta / 2) * n;
            double const along = (p - ps.position(i)).dot(n); // from x_i towards x_j
            bool const between = along > 0.0 && along < d.norm();
            Vec3 const owner =
                between ? p : (ps.radius(i) < ps.radius(j) ? ps.position(i) : ps.position(j));
            if (region.contains(owner))
                out[{ps.uid(i), ps.uid(j)}] = OwnedContact{Contact{i, j, p, n, delta}, owner};
        }
    return out;
}

/// Sphere-wall contacts of the masters (the wall rule does not look at any region).
std::map<std::pair<Uid, std::size_t>, WallContact> bruteForceWalls(ParticleStorage const& ps,
                                                                   WallList const& walls) {
    std::map<std::pair<Uid, std::size_t>, WallContact> out;
    for (std::size_t k = 0; k < ps.size(); ++k)
        for (std::size_t w = 0; w < walls.size(); ++w) {
            if (ps.flags(k).isFixed() || ps.flags(k).isShadow())
                continue;
            double const dist =
                (ps.position(k) - walls[w].geometry.point).dot(walls[w].geometry.normal);
            double const delta = ps.radius(k) - dist;
            Vec3 const p = ps.position(k) - (dist + delta / 2) * walls[w].geometry.normal;
            if (delta > 0.0)
                out[{ps.uid(k), w}] = WallContact{k, w, p, walls[w].geometry.normal, delta};
        }
    return out;
}

/// The brute-force contacts of a set, keyed by uids.
struct Reference {
    std::map<PairKey, OwnedContact> pairs;
    std::map<std::pair<Uid, std::size_t>, WallContact> walls;

    Reference(ParticleStorage const& ps, WallList const& w, AABB const& region = everywhere())
        : pairs(bruteForcePairs(ps, region))
        , walls(bruteForceWalls(ps, w)) {}
    /// The pairs whose ownership point lies in `region` (all the wall contacts).
    [[nodiscard]] Reference within(AABB const& region) const {
        Reference r = *this;
        std::erase_if(r.pairs, [&](auto const& kv) { return !region.contains(kv.second.owner); });
        return r;
    }
};

/// Compares a detector result with the reference: same set, each pair once, canonical order,
/// same geometry to round-off.
void expectSameContacts(ParticleStorage const& ps, Reference const& reference,
                        ContactList const& found) {
    auto const& ref = reference.pairs;
    std::map<PairKey, int> seen;
    for (Contact const& c : found.pairs) {
        EXPECT_LT(ps.uid(c.i), ps.uid(c.j)) << "canonical order";
        PairKey const key{ps.uid(c.i), ps.uid(c.j)};
        EXPECT_EQ(++seen[key], 1) << "pair " << key.first << "," << key.second << " twice";
        auto it = ref.find(key);
        if (it == ref.end()) {
            ADD_FAILURE() << "pair " << key.first << "," << key.second << " is not a contact";
            continue;
        }
        Contact const& r = it->second.contact;
        EXPECT_NEAR(c.penetration, r.penetration, 1e-12);
        EXPECT_LT((c.point - r.point).norm(), 1e-12);
        EXPECT_LT((c.normal - r.normal).norm(), 1e-12);
        EXPECT_EQ(c.shiftJ, Vec3::Zero());
    }
    EXPECT_EQ(found.pairs.size(), ref.size());
    for (auto const& [key, c] : ref)
        EXPECT_TRUE(seen.count(key)) << "missed pair " << key.first << "," << key.second;

    auto const& refWalls = reference.walls;
    EXPECT_EQ(found.walls.size(), refWalls.size());
    for (WallContact const& c : found.walls) {
        auto it = refWalls.find({ps.uid(c.particle), c.wall});
        if (it == refWalls.end()) {
            ADD_FAILURE() << "wall contact " << ps.uid(c.particle) << "," << c.wall;
            continue;
        }
        EXPECT_NEAR(c.penetration, it->second.penetration, 1e-12);
        EXPECT_LT((c.point - it->second.point).norm(), 1e-12);
    }
}

/// A random polydisperse set: log-uniform radii in [0.05, 1], one huge sphere (radius 6) in
/// the middle, ~10 % fixed, uids shuffled against storage order, centres in [0, 20]^3 so that
/// pairs straddle cell boundaries everywhere.
ParticleStorage randomPolydisperse(std::uint64_t seed, std::size_t n) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Uid> uids(n + 1);
    for (std::size_t k = 0; k < uids.size(); ++k)
        uids[k] = makeUid(static_cast<int>(k % 3), k);
    std::shuffle(uids.begin(), uids.end(), rng);
    ParticleStorage ps;
    for (std::size_t k = 0; k < n; ++k) {
        double const r = 0.05 * std::pow(20.0, u(rng));
        ParticleInit p = sphere(uids[k], 20.0 * Vec3(u(rng), u(rng), u(rng)), r, 1.0);
        if (u(rng) < 0.1)
            p.flags = Flag::Fixed;
        ps.add(p);
    }
    ps.add(sphere(uids[n], Vec3(10.0, 10.5, 9.5), 6.0, 100.0));
    return ps;
}

WallList someWalls() {
    WallList walls;
    walls.add(Vec3(0, 0, 0.5), Vec3(0, 0, 1));
    walls.add(Vec3(19.5, 0, 0), Vec3(-1, 0, 0));
    walls.add(Vec3(10, 10, 10), Vec3(1, 1, 1)); // oblique, through the middle
    return walls;
}

} // namespace

TEST(Detection, MatchesBruteForceOnRandomPolydisperseSets) {
    WallList const walls = someWalls();
    for (std::uint64_t seed : {1U, 2U, 3U}) {
        ParticleStorage const ps = randomPolydisperse(seed, 1500);
        Reference const reference(ps, walls);
        for (int variant = 0; variant < 5; ++variant) {
            DetectorConfig cfg;
            if (variant == 1)
                cfg.skin = 0.3;
            if (variant == 2)
                cfg.largeRadius = 0.3; // many "large" spheres: exercises the sweep
            if (variant == 3)
                cfg.maxCellsPerSphere = 1; // the cell edge has to grow
            if (variant == 4)
                cfg.sortByUid = true;
            ContactDetector detector(cfg);
            ContactList found;
            detector.detect(ps, walls, everywhere(), found);
            SCOPED_TRACE(::testing::Message() << "seed " << seed << " variant " << variant);
            expectSameContacts(ps, reference, found);
            EXPECT_GT(found.pairs.size(), 100U);
            EXPECT_GT(found.walls.size(), 10U);
            EXPECT_GE(detector.stats().largeSpheres, 1U);
            EXPECT_GE(detector.stats().cellEdge, 2.0 * 0.05);
            if (variant == 4) {
                EXPECT_TRUE(std::is_sorted(found.pairs.begin(), found.pairs.end(),
                                           [&](Contact const& x, Contact const& y) {
                                               return std::pair(ps.uid(x.i), ps.uid(x.j)) <
                                                      std::pair(ps.uid(y.i), ps.uid(y.j));
                                           }));
            }
        }
    }
}

TEST(Detection, SpatialOrderIsAPermutationThatKeepsTheContacts) {
    ParticleStorage ps = randomPolydisperse(5, 800);
    WallList const walls = someWalls();
    ContactDetector detector;
    ContactList before;
    detector.detect(ps, walls, everywhere(), before);
    auto meanJump = [&ps](std::size_t n) {
        double jumps = 0.0;
        for (std::size_t k = 1; k < n; ++k)
            jumps += (ps.position(k) - ps.position(k - 1)).norm();
        return jumps / static_cast<double>(n - 1);
    };
    std::size_t const small = detector.stats().smallSpheres;
    double const jumpBefore = meanJump(small);
    ps.permute(detector.spatialOrder()); // throws unless a permutation
    ContactList after;
    detector.detect(ps, walls, everywhere(), after);
    expectSameContacts(ps, Reference(ps, walls), after);
    EXPECT_EQ(after.pairs.size(), before.pairs.size());
    EXPECT_EQ(after.walls.size(), before.walls.size());
    // Neighbours in memory are closer in space than in the random input order (mean distance
    // ~13 in a 20^3 box; cell order ~7 for this sparse set, ~1 for a dense one).
    EXPECT_LT(meanJump(small), 0.6 * jumpBefore);
    detector.detect(ParticleStorage{}, walls, everywhere(), after);
    EXPECT_TRUE(detector.spatialOrder().empty());
}

TEST(Detection, EdgeCases) {
    ContactDetector detector;
    ContactList found;
    WallList const walls;
    ParticleStorage ps;
    detector.detect(ps, walls, everywhere(), found);
    EXPECT_EQ(found.size(), 0U);

    // Two far-apart pairs: the cell grid would have 1e15 cells at edge 2 r; it is capped.
    ps.add(sphere(10, Vec3(0, 0, 0), 0.5, 1));
    ps.add(sphere(11, Vec3(0.9, 0, 0), 0.5, 1));
    ps.add(sphere(12, Vec3(1e5, 1e5, 1e5), 0.5, 1));
    ps.add(sphere(13, Vec3(1e5, 1e5, 1e5 + 0.99), 0.5, 1));
    detector.detect(ps, walls, everywhere(), found);
    expectSameContacts(ps, Reference(ps, walls), found);
    EXPECT_EQ(found.pairs.size(), 2U);
    EXPECT_LE(detector.stats().cells, 8U * 4U);

    // Touching exactly (distance == r_i + r_j) is not a contact; coincident centres are.
    ParticleStorage touch;
    touch.add(sphere(1, Vec3(0, 0, 0), 0.5, 1));
    touch.add(sphere(2, Vec3(1.0, 0, 0), 0.5, 1));
    touch.add(sphere(3, Vec3(5, 5, 5), 0.5, 1));
    touch.add(sphere(4, Vec3(5, 5, 5), 0.25, 1));
    detector.detect(touch, walls, everywhere(), found);
    ASSERT_EQ(found.pairs.size(), 1U);
    EXPECT_EQ(touch.uid(found.pairs[0].i), 3U);
    EXPECT_DOUBLE_EQ(found.pairs[0].penetration, 0.75);

    // Two fixed grains are never a contact, a fixed and a free one are.
    ParticleStorage fixed;
    ParticleInit a = sphere(1, Vec3(0, 0, 0), 0.5, 1), b = sphere(2, Vec3(0.8, 0, 0), 0.5, 1);
    a.flags = b.flags = Flag::Fixed;
    fixed.add(a);
    fixed.add(b);
    detector.detect(fixed, walls, everywhere(), found);
    EXPECT_EQ(found.pairs.size(), 0U);
    fixed.setFlags(1, Flags{});
    detector.detect(fixed, walls, everywhere(), found);
    EXPECT_EQ(found.pairs.size(), 1U);
}

TEST(Detection, OneHugeSphereNeitherBlowsUpCellsNorIsCheckedByEveryCell) {
    // A radius-25 sphere in a simple-cubic lattice of ~150,000 grains of radius 0.4 (spacing
    // 1, sites inside radius 25 skipped, so the grains between 25 and 25.4 touch it). The
    // cells keep the small grains' size (0.8), the huge sphere is the only large one, and its
    // pass visits only the cells of its ball, row by row: about 4/3 pi 26.2^3 / 0.8^3 =
    // 147,000 of the ~420,000 cells, and tests only the grains in them.
    ParticleStorage ps;
    Vec3 const c(29.3, 29.6, 29.45);
    ps.add(sphere(1, c, 25.0, 1e5));
    Uid uid = 2;
    std::size_t touching = 0;
    for (int i = 0; i < 60; ++i)
        for (int j = 0; j < 60; ++j)
            for (int k = 0; k < 60; ++k) {
                Vec3 const x(i, j, k);
                double const d = (x - c).norm();
                if (d < 25.0)
                    continue;
                touching += d < 25.4 ? 1 : 0;
                ps.add(sphere(uid++, x, 0.4, 1.0));
            }
    ContactDetector detector;
    ContactList found;
    detector.detect(ps, WallList{}, everywhere(), found);
    auto const& s = detector.stats();
    EXPECT_EQ(s.largeSpheres, 1U);
    // 2 r plus twice the rounding slack (64 ulps of the largest coordinate + 2 r_max, ~1.6e-12).
    EXPECT_DOUBLE_EQ(s.cellEdge, 0.8 + 2.0 * s.slack);
    EXPECT_LT(s.slack, 2e-12);
    double const ballCells = 4.0 / 3.0 * std::numbers::pi * std::pow(25.4 + 0.8, 3) / 0.512;
    EXPECT_LT(static_cast<double>(s.largeCellVisits), 1.2 * ballCells);
    EXPECT_LT(static_cast<double>(s.largeCellVisits), 0.5 * static_cast<double>(s.cells));
    // Only the grains of a thin shell around the huge sphere were tested against it.
    EXPECT_LT(static_cast<double>(s.largeCandidates), 0.15 * static_cast<double>(ps.size()));
    std::size_t withHuge = 0;
    for (Contact const& k : found.pairs)
        withHuge += ps.uid(k.i) == 1 ? 1 : 0;
    EXPECT_EQ(withHuge, touching);
    EXPECT_GT(touching, 1000U);
    EXPECT_EQ(found.pairs.size(), touching); // lattice grains do not touch each other
}

/// The copies a block with box `box` would hold of `all`: the same particles, those whose
/// centre is outside `box` marked Shadow (this test does not care which ones the block would
/// not hold at all: their contacts are not in `box` either).
ParticleStorage asBlock(ParticleStorage const& all, AABB const& box) {
    ParticleStorage part = all;
    for (std::size_t k = 0; k < part.size(); ++k)
        if (!box.contains(part.position(k)))
            part.setFlags(k, part.flags(k) | Flag::Shadow);
    return part;
}

TEST(Detection, EachContactIsKeptByExactlyOneOfAdjacentBoxes) {
    // Spheres of radius 0.75 on a unit lattice: axis neighbours touch at points exactly on the
    // box faces x, y, z = 2.5 (r - delta/2 = 0.5 exactly), diagonal neighbours elsewhere. Eight
    // half-open boxes tile space around (2.5, 2.5, 2.5); together with the random set they
    // must keep every contact exactly once, and a point on a face goes to the upper box. Each
    // box sees the particles whose centre it contains as masters, the others as shadows, and
    // evaluates the wall contacts of its masters only.
    double const inf = std::numeric_limits<double>::infinity();
    std::vector<AABB> boxes;
    for (int b = 0; b < 8; ++b) {
        AABB box;
        for (int d = 0; d < 3; ++d) {
            bool const upper = ((b >> d) & 1) != 0;
            box.min[d] = upper ? 2.5 : -inf;
            box.max[d] = upper ? inf : 2.5;
        }
        boxes.push_back(box);
    }
    ParticleStorage lattice;
    Uid uid = 1;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j)
            for (int k = 0; k < 5; ++k)
                lattice.add(sphere(uid++, Vec3(i, j, k), 0.75, 1.0));
    WallList walls;
    walls.add(Vec3(0, 0, 0.25), Vec3::UnitZ()); // wall contacts too
    {
        ContactDetector detector;
        ContactList all;
        detector.detect(lattice, walls, everywhere(), all);
        std::map<PairKey, int> count;
        std::size_t wallTotal = 0;
        for (AABB const& box : boxes) {
            ParticleStorage const ps = asBlock(lattice, box);
            ContactList part;
            detector.detect(ps, walls, box, part);
            expectSameContacts(ps, Reference(ps, walls).within(box), part);
            for (Contact const& c : part.pairs) {
                ++count[{ps.uid(c.i), ps.uid(c.j)}];
                for (int d = 0; d < 3; ++d) {
                    if (c.point[d] == 2.5) {
                        EXPECT_EQ(box.min[d], 2.5) << "a face point belongs to the upper box";
                    }
                }
            }
            for (WallContact const& c : part.walls)
                EXPECT_TRUE(box.contains(ps.position(c.particle)));
            wallTotal += part.walls.size();
        }
        EXPECT_EQ(count.size(), all.pairs.size());
        for (auto const& [key, n] : count)
            EXPECT_EQ(n, 1) << key.first << "," << key.second;
        EXPECT_EQ(wallTotal, all.walls.size());
        EXPECT_EQ(all.walls.size(), 25U); // the bottom layer, r 0.75 against the wall at 0.25
    }
    // The random polydisperse set, split the same way around its middle. Its radius-6 sphere
    // swallows the centres of small ones: their contact point lies outside the small sphere,
    // so the small centre decides (Reference computes that independently).
    ParticleStorage const all = randomPolydisperse(11, 1500);
    WallList const w = someWalls();
    ContactDetector detector;
    ContactList found;
    detector.detect(all, w, everywhere(), found);
    std::size_t pairs = 0, wallContacts = 0;
    for (AABB box : boxes) {
        box = box.shifted(Vec3::Constant(7.5)); // faces at 10
        ParticleStorage const ps = asBlock(all, box);
        ContactList part;
        detector.detect(ps, w, box, part);
        expectSameContacts(ps, Reference(ps, w).within(box), part);
        pairs += part.pairs.size();
        wallContacts += part.walls.size();
    }
    EXPECT_EQ(pairs, found.pairs.size());
    EXPECT_EQ(wallContacts, found.walls.size());
    std::size_t swallowed = 0;
    for (auto const& [key, c] : Reference(all, w).pairs)
        swallowed += c.owner != c.contact.point ? 1 : 0;
    EXPECT_GT(swallowed, 0U) << "the set exercises the swallowed-centre rule";
}

TEST(Detection, WallContactsAtTouchingDistanceAreThoseOfTheExactTest) {
    // Grains a few ulps either side of touching oblique planes far from the origin (where the
    // distance's rounding is largest), and then with a cylinder among the walls: the
    // detector's screen of the planes must keep every contact the exact test finds.
    WallList planes;
    planes.add(Vec3(1000.0, -2000.0, 3000.0), Vec3(1.0, 2.0, -3.0));
    planes.add(Vec3(1100.5, -1999.5, 3000.25), Vec3(-0.3, 0.1, 0.7));
    WallList withCylinder = planes;
    Wall drum;
    drum.geometry.shape = WallShape::Cylinder;
    drum.geometry.point = Vec3(1000.0, -2000.0, 3000.0);
    drum.geometry.normal = Vec3::UnitZ();
    drum.geometry.radius = 3.0;
    drum.motion.centre = drum.geometry.point;
    withCylinder.add(drum);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    ParticleStorage ps;
    Uid uid = 0;
    for (std::size_t w = 0; w < planes.size(); ++w) {
        WallGeometry const& g = planes[w].geometry;
        for (int k = 0; k < 400; ++k) {
            double const r = 0.1 + 0.05 * (u(rng) + 1.0);
            // A point of the plane, then r along the normal, nudged by up to 8 ulps of r.
            Vec3 foot = g.point + 2.0 * Vec3(u(rng), u(rng), u(rng));
            foot -= (foot - g.point).dot(g.normal) * g.normal;
            double along = r;
            for (int s = static_cast<int>(8.0 * u(rng)); s != 0; s += s > 0 ? -1 : 1)
                along = std::nextafter(along, s > 0 ? 2.0 * r : 0.0);
            ps.add(sphere(uid++, foot + along * g.normal, r, 1.0));
        }
    }
    for (WallList const* walls : {&planes, &withCylinder}) {
        ContactDetector detector;
        ContactList found;
        detector.detect(ps, *walls, everywhere(), found);
        std::map<std::pair<Uid, std::size_t>, int> exact, seen;
        for (std::size_t k = 0; k < ps.size(); ++k)
            for (std::size_t w = 0; w < walls->size(); ++w)
                if (ps.radius(k) - (*walls)[w].distance(ps.position(k)) > 0.0)
                    exact[{ps.uid(k), w}] = 1;
        for (WallContact const& c : found.walls)
            seen[{ps.uid(c.particle), c.wall}] += 1;
        EXPECT_EQ(seen, exact);
        EXPECT_GT(exact.size(), 200U); // about half the grains press on their plane
    }
}
