// Entries in order: a grain is skipped iff it overlaps a kept grain of an earlier entry
// (minimum image on periodic axes); grains of one entry never skip each other. Checked
// against a brute-force oracle that generates each entry alone and applies the rule pairwise.
#include "particles/generators/ParticleGenerator.hpp"
#include "tests/particles/generators/GeneratorTestUtil.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace regolith;
using namespace regolith::testing;
using core::Vec3;

namespace {

/// The rule by brute force: entry k alone (nothing to skip), uids moved to the entry's
/// range, then dropped if it overlaps a kept grain of an entry before k. O(N^2).
std::vector<GrainInit> oracle(std::vector<ParticleSpec> const& specs, core::AABB const& domain,
                              Periodic const& periodic,
                              std::vector<std::uint64_t> const& uidBegin) {
    std::vector<GrainInit> kept;
    for (std::size_t k = 0; k < specs.size(); ++k) {
        std::vector<ParticleSpec> const alone{specs[k]};
        auto grains = particles::generateGrains(alone, domain, periodic).grains;
        std::size_t const before = kept.size();
        for (auto g : grains) {
            bool skip = false;
            for (std::size_t i = 0; i < before && !skip; ++i)
                skip = overlapMinImage(g, kept[i], domain, periodic);
            if (skip)
                continue;
            g.uid += uidBegin[k];
            g.entry = static_cast<std::uint32_t>(k);
            kept.push_back(g);
        }
    }
    return kept;
}

std::size_t countEntry(std::vector<GrainInit> const& g, std::uint32_t entry) {
    return static_cast<std::size_t>(
        std::count_if(g.begin(), g.end(), [&](GrainInit const& x) { return x.entry == entry; }));
}

} // namespace

TEST(Skip, LatticeAroundBoulderSkipsExactlyTheOverlappingSites) {
    // The boulder sits across the periodic x face, so the skip must use the minimum image.
    core::AABB const domain = box(Vec3::Zero(), Vec3(14, 12, 12));
    Periodic const periodic{true, false, false};
    std::vector<ParticleSpec> const specs{sphereList({Vec3(1.3, 6.2, 5.7)}, {3.37}),
                                          lattice(LatticeKind::SimpleCubic, 1.0, 0.45, domain)};
    auto const got = particles::generateGrains(specs, domain, periodic);
    EXPECT_EQ(got.entryUidBegin, (std::vector<std::uint64_t>{0, 1, 1 + 14 * 12 * 12}));
    auto const want = oracle(specs, domain, periodic, got.entryUidBegin);
    expectSameGrains(got.grains, want, "boulder + sc");
    // A sphere of radius 3.37 + 0.45 removes about 4/3 pi 3.82^3 = 233 sites, some of them
    // on the far side of the x face.
    std::size_t const skipped = 14 * 12 * 12 - countEntry(got.grains, 1);
    EXPECT_GT(skipped, 200u);
    EXPECT_LT(skipped, 270u);
    EXPECT_TRUE(std::any_of(got.grains.begin(), got.grains.end(), [](GrainInit const& g) {
        return g.entry == 1 && g.position.x() > 10.0 && std::abs(g.position.y() - 6.2) < 1 &&
               std::abs(g.position.z() - 5.7) < 1;
    })) << "sanity: the lattice exists far from the image";
    EXPECT_FALSE(std::any_of(got.grains.begin(), got.grains.end(), [](GrainInit const& g) {
        return g.entry == 1 && g.position.x() > 12.5 && std::abs(g.position.y() - 6.2) < 1 &&
               std::abs(g.position.z() - 5.7) < 1;
    })) << "sites near the boulder's periodic image must be skipped";
}

TEST(Skip, SameEntryOverlapsAreKeptLaterEntriesSkipAgainstAllEarlier) {
    core::AABB const domain = box(Vec3::Zero(), Vec3(9, 9, 9));
    Periodic const periodic{true, true, true};
    std::vector<ParticleSpec> const specs{
        // GranularGas: radius 0.6 at spacing 1 overlaps its neighbours, all kept.
        lattice(LatticeKind::SimpleCubic, 1.0, 0.6, box(Vec3::Zero(), Vec3(9, 9, 4))),
        // Interleaved finer hcp over the top half and the lattice's top layer.
        lattice(LatticeKind::HexagonalClosePacked, 0.7, 0.3, box(Vec3(0, 0, 3.2), Vec3(9, 9, 9))),
        // A list whose grains overlap each other (kept) and both lattices (skipped).
        sphereList(
            {Vec3(4.4, 4.4, 6.3), Vec3(5.0, 4.4, 6.3), Vec3(2.2, 2.2, 4.0), Vec3(8.9, 0.1, 8.9)},
            {0.5, 0.5, 0.5, 0.2}),
        lattice(LatticeKind::SimpleCubic, 0.5, 0.2, box(Vec3(3, 3, 3), Vec3(6, 6, 8)))};
    auto const got = particles::generateGrains(specs, domain, periodic);
    EXPECT_EQ(countEntry(got.grains, 0), 9u * 9 * 4);
    auto const want = oracle(specs, domain, periodic, got.entryUidBegin);
    expectSameGrains(got.grains, want, "four entries, periodic");
    EXPECT_GT(countEntry(got.grains, 1), 0u);
    EXPECT_LT(countEntry(got.grains, 3), 6u * 6 * 10);
}

TEST(Skip, WalledDomainWithBoulderAfterLattice) {
    // A boulder listed after the lattice is itself skipped if it overlaps a lattice grain:
    // the order of the entries decides, as docs/design.md says ("Scene file").
    core::AABB const domain = box(Vec3::Zero(), Vec3(8, 8, 8));
    Periodic const periodic{false, false, false};
    std::vector<ParticleSpec> const specs{
        lattice(LatticeKind::SimpleCubic, 1.0, 0.45, box(Vec3::Zero(), Vec3(8, 8, 4))),
        sphereList({Vec3(4, 4, 6), Vec3(3.5, 3.5, 4.2)}, {1.5, 0.3})};
    auto const got = particles::generateGrains(specs, domain, periodic);
    auto const want = oracle(specs, domain, periodic, got.entryUidBegin);
    expectSameGrains(got.grains, want, "lattice then boulders");
    ASSERT_EQ(countEntry(got.grains, 1), 1u);
    EXPECT_EQ(got.grains.back().uid, got.entryUidBegin[1]); // the first (upper) boulder
}
