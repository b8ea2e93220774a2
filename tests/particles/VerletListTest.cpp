// The Verlet list of ContactDetector (detect on a mutable storage with a skin) finds exactly
// the contacts of the linked cells rebuilt every call, bit for bit, while the storage changes
// under it as the synchronisation changes it: grains move, copies arrive, leave (moving others
// to new indices) and change their periodic image; and it is reused, not rebuilt every call.
#include "particles/detection/VerletList.hpp"

#include "particles/detection/ContactDetector.hpp"
#include "particles/detection/PairRule.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "tests/particles/ParticleTestUtil.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <tuple>
#include <vector>

using namespace regolith::particles;
using namespace regolith::particles::test;
using regolith::core::AABB;

namespace {

using Key = std::tuple<Uid, Uid, CopyImage>;

/// Contacts by (uid_i, uid_j, image difference), with the bits of their penetration.
std::map<Key, std::uint64_t> byKey(ParticleStorage const& ps, ContactList const& list) {
    std::map<Key, std::uint64_t> out;
    for (Contact const& c : list.pairs) {
        Key const k{ps.uid(c.i), ps.uid(c.j), subtractImages(ps.image(c.j), ps.image(c.i))};
        EXPECT_TRUE(out.emplace(k, std::bit_cast<std::uint64_t>(c.penetration)).second)
            << "a pair emitted twice";
    }
    return out;
}

struct Scene {
    PeriodicFrame frame{AABB{Vec3::Zero(), Vec3::Constant(6.0)}, {true, true, false}};
    AABB region{Vec3::Zero(), Vec3(6.0, 6.0, 6.0)};
    std::mt19937_64 rng{7};
    Uid next = 0;
    double fixedShare = 0.0;  ///< of the copies made Fixed
    double largeShare = 0.05; ///< of the copies made large (r 0.8-1.5)

    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
    ParticleInit randomCopy() {
        // Mostly small grains, a few large ones; some at a periodic image on x or y.
        double const r = uniform(0.0, 1.0) < largeShare ? uniform(0.8, 1.5) : uniform(0.2, 0.3);
        ParticleInit p =
            sphere(next++, Vec3(uniform(0.0, 6.0), uniform(0.0, 6.0), uniform(0.0, 6.0)), r, 1.0);
        if (uniform(0.0, 1.0) < 0.2)
            p.image = CopyImage{static_cast<std::int8_t>(uniform(0.0, 1.0) < 0.5 ? -1 : 1), 0, 0};
        if (uniform(0.0, 1.0) < 0.1)
            p.flags.set(Flag::Shadow, true);
        if (fixedShare > 0.0 && uniform(0.0, 1.0) < fixedShare)
            p.flags.set(Flag::Fixed, true);
        return p;
    }
};

/// The list's skin: 0.1, or chosen for the scene (ContactDetector, "A skin for the scene").
DetectorConfig absoluteSkin() {
    DetectorConfig c;
    c.skin = 0.1;
    return c;
}

/// The scene of SameContactsAsCells... with evaluation region `region` (settled pairs are
/// decided against it) and the list configured by `withSkin`: returns the settled pairs seen,
/// over all calls. With `overlapsOnly` the fused loop hands over PairOverlaps and keeps no
/// contacts (the block-wise overlap screen, as DemStep runs it); the contacts compared are
/// the geometry of the pairs handed over. `mix.fixedShare` of the copies are Fixed (a pair of
/// two is never a contact). With withSkin.keepSprings the callback takes kept springs, so that
/// the pairs known to overlap (PairMode::KeptPressed) are handed on untested among the others.
/// The copies of that scene: how many, and the shares made Fixed and large.
struct Mix {
    int copies = 400;
    double fixedShare = 0.0;
    double largeShare = 0.05;
};

std::size_t sameContactsAsCells(AABB const& region, DetectorConfig withSkin = absoluteSkin(),
                                bool overlapsOnly = false, Mix mix = {}) {
    Scene s;
    s.region = region;
    s.fixedShare = mix.fixedShare;
    s.largeShare = mix.largeShare;
    ParticleStorage ps;
    for (int k = 0; k < mix.copies; ++k)
        ps.add(s.randomCopy());
    ContactDetector listed(withSkin);
    ContactDetector cells;
    std::size_t rebuilds = 0, arrivals = 0, contacts = 0, settled = 0, listedMost = 0;
    std::size_t keptHanded = 0, pressedMost = 0;
    for (int step = 0; step < 300; ++step) {
        listed.writeBackSprings(ps); // before the storage changes (ContactDetector's contract)
        // Moves of up to skin/8 per call, and now and then one far jump.
        for (std::size_t k = 0; k < ps.size(); ++k)
            ps.position(k) +=
                Vec3(s.uniform(-1.0, 1.0), s.uniform(-1.0, 1.0), s.uniform(-1.0, 1.0)) * 0.0072;
        if (step % 37 == 5)
            ps.position(step % ps.size()) += Vec3(0.3, 0.0, 0.0);
        // The synchronisation's changes: removals (swap with the last), arrivals, re-keys.
        int const changes = static_cast<int>(s.uniform(0.0, 4.0));
        for (int c = 0; c < changes; ++c) {
            ps.remove(static_cast<std::size_t>(s.uniform(0.0, static_cast<double>(ps.size()))));
            ps.add(s.randomCopy());
        }
        if (step % 11 == 3) {
            std::size_t const k = static_cast<std::size_t>(step) % ps.size();
            CopyImage im = ps.image(k);
            im[1] = static_cast<std::int8_t>(im[1] == 0 ? 1 : 0);
            ps.setImage(k, im);
        }
        ContactList a, b;
        DetectorStats stats; // of the detection compared
        if (overlapsOnly) {
            ContactList none;
            auto const take = [&](PairOverlap const& o) {
                Contact c;
                EXPECT_TRUE(detection_detail::overlapGeometry(ps, o.i, o.j, s.frame.period(), c));
                EXPECT_EQ(c.shiftJ, o.shiftJ);
                a.pairs.push_back(c);
            };
            if (withSkin.keepSprings) {
                struct KeepsSprings {
                    decltype(take) const& onPair;
                    std::size_t& kept;
                    std::uint32_t stamp;
                    void operator()(PairOverlap const& o, std::uint8_t&) { onPair(o); }
                    void operator()(PairOverlap const& o, KeptSpring& spring) {
                        spring.stamp = stamp;
                        ++kept;
                        onPair(o);
                    }
                    [[nodiscard]] std::uint32_t pass() const { return stamp; }
                } keeps{take, keptHanded, static_cast<std::uint32_t>(step + 1)};
                listed.detect(ps, {}, s.region, s.frame, none, keeps, false);
            } else {
                listed.detect(
                    ps, {}, s.region, s.frame, none,
                    [&](PairOverlap const& o, std::uint8_t&) { take(o); }, false);
            }
            EXPECT_TRUE(none.pairs.empty());
            stats = listed.stats();
            pressedMost = std::max(pressedMost, stats.pressedPairs);
            // In list order: as the pass that keeps its contacts hands them (nothing moved
            // since: the list is neither rebuilt nor shifted).
            ContactList inOrder;
            listed.noteMotion(0.0);
            listed.detect(ps, {}, s.region, s.frame, inOrder);
            EXPECT_FALSE(listed.stats().rebuilt);
            EXPECT_EQ(listed.stats().shifts, 0U);
            EXPECT_EQ(inOrder.pairs.size(), a.pairs.size());
            for (std::size_t k = 0; k < std::min(inOrder.pairs.size(), a.pairs.size()); ++k) {
                EXPECT_EQ(inOrder.pairs[k].i, a.pairs[k].i) << k;
                EXPECT_EQ(inOrder.pairs[k].j, a.pairs[k].j) << k;
            }
            listedMost = std::max(listedMost, listed.stats().listedPairs);
        } else {
            // The fused loop hands over exactly the contacts it lists, in order.
            std::vector<Contact> handed;
            listed.detect(ps, {}, s.region, s.frame, a,
                          [&](Contact const& c, std::uint8_t&) { handed.push_back(c); });
            EXPECT_EQ(handed.size(), a.pairs.size());
            for (std::size_t k = 0; k < std::min(handed.size(), a.pairs.size()); ++k)
                EXPECT_EQ(std::bit_cast<std::uint64_t>(handed[k].penetration),
                          std::bit_cast<std::uint64_t>(a.pairs[k].penetration));
            stats = listed.stats();
        }
        settled += stats.settledPairs;
        rebuilds += stats.rebuilt ? 1 : 0;
        arrivals += stats.arrivals;
        cells.detect(std::as_const(ps), {}, s.region, s.frame, b);
        auto const fromList = byKey(ps, a);
        EXPECT_EQ(fromList, byKey(ps, b)) << "step " << step;
        if (fromList != byKey(ps, b))
            return settled;
        contacts += fromList.size();
    }
    EXPECT_GT(contacts, 1000U); // the scene has contacts to find
    EXPECT_GT(arrivals, 100U);  // copies arrived between rebuilds and were followed
    EXPECT_LT(rebuilds, 150U);  // and the list was reused
    EXPECT_GT(rebuilds, 5U);    // but rebuilt when grains moved skin/2
    if (overlapsOnly) {         // blocks carried over from one stretch of the list to the next
        EXPECT_GT(listedMost, 2 * VerletList::kBlock);
    }
    if (withSkin.keepSprings) { // pairs handed on untested, in their places among the tested
        EXPECT_GT(pressedMost, 20U);
        EXPECT_GT(keptHanded, 1000U);
    }
    return settled;
}

TEST(VerletList, SameContactsAsCellsWhileTheStorageChanges) {
    // Region = the domain: pairs are settled against the periodic faces only.
    EXPECT_GT(sameContactsAsCells(AABB{Vec3::Zero(), Vec3(6.0, 6.0, 6.0)}), 0U);
}

TEST(VerletList, SameContactsAsCellsInOneBlockOfSeveral) {
    // A block of a 2 x 2 x 1 forest: pairs are settled against its faces (evaluated here
    // always, never) and those near a face keep the contact-point rule.
    EXPECT_GT(sameContactsAsCells(AABB{Vec3(3.0, 0.0, 0.0), Vec3(6.0, 3.0, 6.0)}), 0U);
}

TEST(VerletList, SameContactsAsCellsScreenedBlockWise) {
    // The pairs DemStep's loop is handed (PairOverlap, no contacts kept), in a block of a
    // 2 x 2 x 1 forest and in the whole domain: the pairs near a face ruled where they
    // overlap, and a third of the copies Fixed (the rule drops a pair of two).
    AABB const block{Vec3(3.0, 0.0, 0.0), Vec3(6.0, 3.0, 6.0)};
    AABB const domain{Vec3::Zero(), Vec3(6.0, 6.0, 6.0)};
    EXPECT_GT(sameContactsAsCells(block, absoluteSkin(), true), 0U);
    EXPECT_GT(sameContactsAsCells(domain, absoluteSkin(), true), 0U);
    EXPECT_GT(sameContactsAsCells(block, absoluteSkin(), true, Mix{.fixedShare = 0.33}), 0U);
}

TEST(VerletList, SameContactsAsCellsScreenedBlockWiseWithKeptSprings) {
    DetectorConfig config = absoluteSkin();
    config.keepSprings = true;
    sameContactsAsCells(AABB{Vec3(0.0, 0.0, 0.0), Vec3(6.0, 6.0, 6.0)}, config, true);
}

TEST(VerletList, SameContactsAsCellsWithKeptSpringsAndNoLargeGrains) {
    // Without the large grains no pair can meet through two periodic images of the 6^3
    // domain, so a rebuild settles the pairs of two masters deep inside the block at once
    // (ContactDetector::deepMasters) and the others one by one: both must list what the
    // cells find, in the whole domain and in a block of a 2 x 2 x 1 forest.
    DetectorConfig config = absoluteSkin();
    config.keepSprings = true;
    AABB const domain{Vec3::Zero(), Vec3(6.0, 6.0, 6.0)};
    AABB const block{Vec3(3.0, 0.0, 0.0), Vec3(6.0, 3.0, 6.0)};
    Mix const small{.copies = 1200, .largeShare = 0.0};
    EXPECT_GT(sameContactsAsCells(domain, config, true, small), 0U);
    EXPECT_GT(sameContactsAsCells(block, config, true, small), 0U);
}

TEST(VerletList, SameContactsAsCellsWithTheSkinChosenForTheScene) {
    DetectorConfig chosen;
    chosen.relativeSkin = 0.25;
    chosen.widestRelativeSkin = 0.75;
    EXPECT_GT(sameContactsAsCells(AABB{Vec3::Zero(), Vec3(6.0, 6.0, 6.0)}, chosen), 0U);
}

/// The skin chosen at the first rebuild of equal spheres of radius 0.5 on a simple cubic
/// lattice of spacing `spacing` (in a periodic box of 8 x 8 x 8 sites).
double skinChosenForLattice(double spacing) {
    double const edge = 8.0 * spacing;
    PeriodicFrame const frame{AABB{Vec3::Zero(), Vec3::Constant(edge)}, {true, true, true}};
    ParticleStorage ps;
    Uid uid = 0;
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x)
                ps.add(sphere(uid++, spacing * Vec3(x + 0.5, y + 0.5, z + 0.5), 0.5, 1.0));
    DetectorConfig chosen;
    chosen.relativeSkin = 0.25;
    chosen.widestRelativeSkin = 0.75;
    ContactDetector listed(chosen);
    ContactList out;
    listed.detect(ps, {}, frame.domain, frame, out);
    EXPECT_TRUE(listed.stats().rebuilt);
    return listed.stats().skin;
}

TEST(VerletList, APackingTakesAWiderSkinThanAGas) {
    // Touching spheres: the next sites lie sqrt(2) - 1 = 0.41 beyond contact, so every
    // candidate up to 0.75 r = 0.375 lists the same six neighbours: the widest is taken.
    EXPECT_DOUBLE_EQ(skinChosenForLattice(1.0), 0.375);
    // Sites 1.1 apart (gap 0.1): every candidate lists the six neighbours (the next sites
    // lie sqrt(2) 1.1 - 1 = 0.56 beyond contact): the widest again.
    EXPECT_DOUBLE_EQ(skinChosenForLattice(1.1), 0.375);
    // Sites 1.2 apart (gap 0.2): 0.125 lists nothing, 0.25 the six neighbours: the first
    // candidate is kept (a list that grows from nothing is not "hardly longer").
    EXPECT_DOUBLE_EQ(skinChosenForLattice(1.2), 0.125);
}

TEST(VerletList, RebuildsWhenTheTraceBreaks) {
    Scene s;
    ParticleStorage ps;
    for (int k = 0; k < 50; ++k)
        ps.add(s.randomCopy());
    DetectorConfig withSkin;
    withSkin.relativeSkin = 0.5;
    ContactDetector listed(withSkin);
    ContactList out;
    listed.detect(ps, {}, s.region, s.frame, out);
    EXPECT_TRUE(listed.stats().rebuilt);
    EXPECT_NEAR(listed.stats().skin, 0.15, 0.01); // half the largest small radius
    listed.detect(ps, {}, s.region, s.frame, out);
    EXPECT_FALSE(listed.stats().rebuilt);
    ps.setRadius(0, ps.radius(0) * 2.0);
    listed.detect(ps, {}, s.region, s.frame, out);
    EXPECT_TRUE(listed.stats().rebuilt);
    // Pairs of two Fixed copies are not contacts: the settled pairs assume Fixed stays.
    ps.setFlags(3, Flags(ps.flags(3)).set(Flag::Fixed));
    listed.detect(ps, {}, s.region, s.frame, out);
    EXPECT_TRUE(listed.stats().rebuilt);
    ParticleStorage other = ps; // another storage with the same trace
    listed.detect(other, {}, s.region, s.frame, out);
    EXPECT_TRUE(listed.stats().rebuilt);
    std::vector<std::size_t> reverse;
    for (std::size_t k = ps.size(); k-- > 0;)
        reverse.push_back(k);
    other.permute(reverse);
    listed.detect(other, {}, s.region, s.frame, out);
    EXPECT_TRUE(listed.stats().rebuilt);
}

TEST(VerletList, TheDetectorsQuietMotionEndsWithAChangeOfItsStorage) {
    Scene s;
    ParticleStorage ps;
    for (int k = 0; k < 50; ++k)
        ps.add(s.randomCopy());
    double const inf = std::numeric_limits<double>::infinity();
    ContactList out;
    EXPECT_EQ(ContactDetector().quietMotion(ps, s.region, s.frame), inf); // no list
    DetectorConfig withSkin;
    withSkin.relativeSkin = 0.5;
    ContactDetector listed(withSkin);
    EXPECT_EQ(listed.quietMotion(ps, s.region, s.frame), -inf); // none built yet
    listed.detect(ps, {}, s.region, s.frame, out);
    double const quiet = listed.quietMotion(ps, s.region, s.frame);
    EXPECT_GT(quiet, 0.0);
    EXPECT_LT(quiet, inf);
    // Moved within it: prepareList finds the list not due, and the detect keeps it.
    listed.noteMotion(quiet);
    EXPECT_FALSE(listed.prepareList(ps, s.region, s.frame).due);
    listed.detect(ps, {}, s.region, s.frame, out);
    EXPECT_FALSE(listed.stats().rebuilt);
    // Another region, or a copy added since the last detect: no motion rules a rebuild out.
    AABB const other{Vec3::Zero(), Vec3(3.0, 6.0, 6.0)};
    EXPECT_EQ(listed.quietMotion(ps, other, s.frame), -inf);
    ps.add(s.randomCopy());
    EXPECT_EQ(listed.quietMotion(ps, s.region, s.frame), -inf);
    listed.detect(ps, {}, s.region, s.frame, out);
    EXPECT_GT(listed.quietMotion(ps, s.region, s.frame), 0.0);
}

TEST(VerletList, ItsWalkFollowsTheStoragesLayout) {
    // A row of eight touching copies, a pair per neighbour. The walk looks the copies' indices
    // up once; after a removal (the last copy takes the removed one's slot) and follow(), it
    // hands over the new indices, without the removed copy's pairs.
    ParticleStorage ps;
    for (Uid u = 1; u <= 8; ++u)
        ps.add(sphere(u, Vec3(double(u), 0.0, 0.0), 0.5, 1.0));
    VerletList list;
    list.restart(ps, 0.1);
    for (VerletList::Id k = 0; k + 1 < 8; ++k)
        list.addPair(k, k + 1);
    using Walked = std::vector<std::array<std::size_t, 3>>;
    auto const walk = [&list] {
        Walked out;
        list.forEachNearBlock([&](std::uint32_t const* a, std::uint32_t const* b,
                                  std::uint32_t const* p, std::size_t n) {
            for (std::size_t k = 0; k < n; ++k)
                out.push_back({a[k], b[k], p[k]});
        });
        return out;
    };
    EXPECT_EQ(
        walk(),
        (Walked{{0, 1, 0}, {1, 2, 1}, {2, 3, 2}, {3, 4, 3}, {4, 5, 4}, {5, 6, 5}, {6, 7, 6}}));
    ps.remove(2);
    std::vector<std::size_t> fresh;
    ASSERT_TRUE(list.follow(ps, fresh));
    EXPECT_TRUE(fresh.empty());
    EXPECT_EQ(walk(), (Walked{{0, 1, 0}, {3, 4, 3}, {4, 5, 4}, {5, 6, 5}, {6, 2, 6}}));
}

} // namespace
