// Lattice entries: sc and hcp site counts and positions against independent enumerations,
// nearest-neighbour distances and coordination, the site rule on periodic and walled axes,
// the hcp packing fraction, and random velocities.
#include "core/random/CounterRng.hpp"
#include "particles/generators/ParticleGenerator.hpp"
#include "tests/particles/generators/GeneratorTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

using namespace regolith;
using namespace regolith::testing;
using core::Vec3;

namespace {

std::vector<GrainInit> generateOne(ParticleSpec const& spec, core::AABB const& domain,
                                   Periodic const& periodic) {
    std::vector<ParticleSpec> const specs{spec};
    return particles::generateGrains(specs, domain, periodic).grains;
}

/// Pairs at distance d within tol, and the smallest distance, by brute force.
struct PairStats {
    std::size_t pairsAtSpacing = 0;
    double minDistance = 1e300;
};
PairStats pairStats(std::vector<GrainInit> const& g, double spacing) {
    PairStats s;
    for (std::size_t a = 0; a < g.size(); ++a)
        for (std::size_t b = a + 1; b < g.size(); ++b) {
            double const d = (g[a].position - g[b].position).norm();
            s.minDistance = std::min(s.minDistance, d);
            if (std::abs(d - spacing) < 1e-9 * spacing)
                ++s.pairsAtSpacing;
        }
    return s;
}

/// hcp centres from the textbook formula for spheres of radius r' = spacing / 2
/// (x, y, z) = r' (2i + ((j + k) mod 2), sqrt(3) (j + (k mod 2) / 3), 2 sqrt(6) / 3 k),
/// shifted by region.min + r', filtered by the site rule; sorted. On a periodic x the
/// shifted rows (j + k odd) start one r' lower, at region.min, and have the same indices i
/// as the other rows (those whose unshifted centre is below region.max).
std::vector<Vec3> hcpReference(double spacing, double radius, core::AABB const& region,
                               Periodic const& periodic) {
    double const rp = spacing / 2.0;
    std::vector<Vec3> out;
    for (int k = 0; k < 200; ++k)
        for (int j = 0; j < 200; ++j)
            for (int i = 0; i < 200; ++i) {
                bool const shifted = (j + k) % 2 != 0;
                int const xUnits = shifted && periodic[0] ? 2 * i - 1 : 2 * i + (shifted ? 1 : 0);
                if (shifted && periodic[0] && region.min.x() + rp * (2 * i + 1) >= region.max.x())
                    continue;
                Vec3 const c = region.min.array() + rp +
                               Vec3(rp * xUnits, rp * std::sqrt(3.0) * (j + (k % 2) / 3.0),
                                    rp * 2.0 * std::sqrt(6.0) / 3.0 * k)
                                   .array();
                bool ok = true;
                for (int a = 0; a < 3; ++a)
                    ok = ok && (periodic[static_cast<std::size_t>(a)]
                                    ? c[a] >= region.min[a] && c[a] < region.max[a] - 1e-9
                                    : c[a] - radius >= region.min[a] - 1e-9 &&
                                          c[a] + radius <= region.max[a] + 1e-9);
                if (ok)
                    out.push_back(c);
            }
    std::sort(out.begin(), out.end(), [](Vec3 const& a, Vec3 const& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    return out;
}

std::vector<Vec3> sortedPositions(std::vector<GrainInit> const& g) {
    std::vector<Vec3> p;
    for (auto const& x : g)
        p.push_back(x.position);
    std::sort(p.begin(), p.end(), [](Vec3 const& a, Vec3 const& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    return p;
}

} // namespace

TEST(LatticeSc, CountsPositionsAndNeighbours) {
    core::AABB const domain = box(Vec3::Zero(), Vec3(10, 10, 10));
    auto const g = generateOne(lattice(LatticeKind::SimpleCubic, 1.0, 0.4, domain), domain,
                               {false, false, false});
    ASSERT_EQ(g.size(), 1000u);
    for (std::size_t n = 0; n < g.size(); ++n) {
        // uid = i + 10 (j + 10 k), centre 0.5 + (i, j, k): both fixed by the contract.
        auto const i = static_cast<double>(n % 10);
        auto const j = static_cast<double>((n / 10) % 10);
        auto const k = static_cast<double>(n / 100);
        EXPECT_EQ(g[n].uid, n);
        EXPECT_EQ(g[n].position, Vec3(0.5 + i, 0.5 + j, 0.5 + k));
        EXPECT_DOUBLE_EQ(g[n].mass, 4.0 / 3.0 * std::numbers::pi * 0.4 * 0.4 * 0.4 * 2.5);
    }
    auto const s = pairStats(g, 1.0);
    EXPECT_DOUBLE_EQ(s.minDistance, 1.0);
    EXPECT_EQ(s.pairsAtSpacing, 3u * 10 * 10 * 9); // bonds along the three axes
}

TEST(LatticeSc, SiteRuleOnPeriodicAndWalledAxes) {
    core::AABB const domain = box(Vec3::Zero(), Vec3(10, 10, 10));
    auto const spec = lattice(LatticeKind::SimpleCubic, 1.0, 0.6, domain);
    // Walls: a grain must fit, so the layers at 0.5 and 9.5 (reaching 0.6 out) are dropped.
    EXPECT_EQ(generateOne(spec, domain, {false, false, false}).size(), 8u * 8 * 8);
    // Periodic: centres in [0, 10) -- the MESA-PD GranularGas lattice, overlaps and all.
    EXPECT_EQ(generateOne(spec, domain, {true, true, true}).size(), 1000u);
    EXPECT_EQ(generateOne(spec, domain, {true, true, false}).size(), 10u * 10 * 8);
    // A region that is not a multiple of the spacing: the centre 10.5 is in [0, 10.7) but its
    // grain would reach 10.9 > 10.7.
    core::AABB const big = box(Vec3::Zero(), Vec3(11, 11, 11));
    auto const odd =
        lattice(LatticeKind::SimpleCubic, 1.0, 0.4, box(Vec3::Zero(), Vec3(10.7, 10.7, 10.7)));
    EXPECT_EQ(generateOne(odd, big, {false, false, false}).size(), 1000u);
    EXPECT_EQ(generateOne(odd, big, {true, true, true}).size(), 11u * 11 * 11);
}

TEST(LatticeSc, LargePeriodicLatticeHasOneGrainPerCell) {
    // The example of GeneratorSpec.hpp, at 40: spacing 1 in [0, 40)^3 periodic gives 40^3 grains.
    core::AABB const domain = box(Vec3::Zero(), Vec3(40, 40, 40));
    auto const g = generateOne(lattice(LatticeKind::SimpleCubic, 1.0, 0.4, domain), domain,
                               {true, true, true});
    EXPECT_EQ(g.size(), 40u * 40 * 40);
    EXPECT_EQ(g.back().uid, 40u * 40 * 40 - 1);
}

TEST(LatticeHcp, MatchesTextbookCoordinatesAndHasTwelveNeighbours) {
    core::AABB const domain = box(Vec3::Zero(), Vec3(7.3, 6.1, 5.2));
    for (Periodic const periodic : {Periodic{false, false, false}, Periodic{true, true, true}}) {
        auto const g = generateOne(lattice(LatticeKind::HexagonalClosePacked, 1.0, 0.5, domain),
                                   domain, periodic);
        auto const want = hcpReference(1.0, 0.5, domain, periodic);
        auto const got = sortedPositions(g);
        ASSERT_EQ(got.size(), want.size());
        EXPECT_GT(got.size(), 100u);
        for (std::size_t i = 0; i < got.size(); ++i)
            EXPECT_LT((got[i] - want[i]).norm(), 1e-12) << i;
        // Contact distance is the spacing; no closer pair; an interior sphere touches 12.
        auto const s = pairStats(g, 1.0);
        EXPECT_NEAR(s.minDistance, 1.0, 1e-12);
        Vec3 const middle = domain.center();
        auto const inner = std::min_element(g.begin(), g.end(), [&](auto const& a, auto const& b) {
            return (a.position - middle).norm() < (b.position - middle).norm();
        });
        int touching = 0;
        int secondShell = 0;
        for (auto const& x : g) {
            double const d = (x.position - inner->position).norm();
            touching += std::abs(d - 1.0) < 1e-9 ? 1 : 0;
            secondShell += std::abs(d - std::sqrt(2.0)) < 1e-9 ? 1 : 0;
        }
        EXPECT_EQ(touching, 12);
        EXPECT_EQ(secondShell, 6); // hcp: 6 at sqrt(2) d (fcc would have 6 too, 12 at sqrt(3))
        // Layers ABAB: z spacing sqrt(2/3), layer B shifted by (1/2, sqrt(3)/6).
        std::map<double, int> layers;
        for (auto const& x : g)
            ++layers[x.position.z()];
        double previous = -1.0;
        for (auto const& [z, n] : layers) {
            if (previous >= 0.0) {
                EXPECT_NEAR(z - previous, std::sqrt(2.0 / 3.0), 1e-12);
            }
            previous = z;
            EXPECT_GT(n, 0);
        }
    }
}

TEST(LatticeHcp, TilesAPeriodicXWithoutHoleOrOverlap) {
    // Periodic in x and y with whole periods (8 spacings, 8 rows), walls in z: every row of
    // every layer has 8 sites, and across the faces each grain touches its 6 in-layer
    // neighbours at the spacing exactly (the minimum image distance is the spacing).
    double const rowPeriod = 8.0 * std::sqrt(3.0) / 2.0;
    core::AABB const domain = box(Vec3::Zero(), Vec3(8.0, rowPeriod, 4.0));
    Periodic const periodic{true, true, false};
    auto const g =
        generateOne(lattice(LatticeKind::HexagonalClosePacked, 1.0, 0.5, domain), domain, periodic);
    std::map<std::pair<double, double>, int> rows;
    for (auto const& x : g)
        ++rows[{x.position.z(), x.position.y()}];
    EXPECT_EQ(rows.size(), 8u * 4); // 8 rows in each of the 4 layers that fit in z
    for (auto const& [row, n] : rows)
        EXPECT_EQ(n, 8) << "row at z " << row.first << ", y " << row.second;
    auto const minimumImage = [&](Vec3 d) {
        for (int a = 0; a < 2; ++a)
            d[a] -= domain.extent()[a] * std::round(d[a] / domain.extent()[a]);
        return d.norm();
    };
    for (auto const& a : g) {
        int inLayer = 0;
        for (auto const& b : g) {
            if (&a == &b)
                continue;
            double const d = minimumImage(b.position - a.position);
            EXPECT_GT(d, 1.0 - 1e-9) << a.uid << " " << b.uid;
            inLayer += (std::abs(d - 1.0) < 1e-9 && b.position.z() == a.position.z()) ? 1 : 0;
        }
        EXPECT_EQ(inLayer, 6) << "uid " << a.uid;
    }
    // A period that is not a multiple of the spacing (9.25): every row keeps 9 sites (the
    // shifted ones x = 0 ... 8, the others 0.5 ... 8.5), and nothing overlaps across the face.
    core::AABB const odd = box(Vec3::Zero(), Vec3(9.25, rowPeriod, 4.0));
    auto const h =
        generateOne(lattice(LatticeKind::HexagonalClosePacked, 1.0, 0.5, odd), odd, periodic);
    EXPECT_EQ(h.size(), 9u * 8 * 4);
    for (auto const& a : h)
        for (auto const& b : h) {
            if (&a == &b)
                continue;
            Vec3 d = b.position - a.position;
            d.x() -= 9.25 * std::round(d.x() / 9.25);
            d.y() -= rowPeriod * std::round(d.y() / rowPeriod);
            EXPECT_GT(d.norm(), 1.0 - 1e-9) << a.uid << " " << b.uid;
        }
}

TEST(LatticeHcp, PackingFractionOfLargeRegion) {
    // Centres in [0, L)^3 (periodic): N / V -> sqrt(2) / d^3, phi -> pi / (3 sqrt 2) = 0.7405.
    // Boundary effects: 24 is not a whole number of rows in y or layers in z, about 1 / L
    // per axis (4.1 % in all at L = 24), so the
    // whole-region fraction is checked to 5 % and the density of an interior box to 2 %.
    core::AABB const domain = box(Vec3::Zero(), Vec3(24, 24, 24));
    auto const g = generateOne(lattice(LatticeKind::HexagonalClosePacked, 1.0, 0.5, domain), domain,
                               {true, true, true});
    double volume = 0.0;
    for (auto const& x : g)
        volume += 4.0 / 3.0 * std::numbers::pi * std::pow(x.radius, 3);
    double const phi = volume / domain.volume();
    EXPECT_NEAR(phi, std::numbers::pi / (3.0 * std::sqrt(2.0)), 0.05 * 0.7405);
    // The density of sites away from the faces is exact: count in the central box.
    core::AABB const inner = box(Vec3(6, 6, 6), Vec3(18, 18, 18));
    std::size_t n = 0;
    for (auto const& x : g)
        n += inner.contains(x.position) ? 1 : 0;
    EXPECT_NEAR(static_cast<double>(n) * (std::numbers::pi / 6.0) / inner.volume(), 0.7405, 0.02);
}

TEST(LatticeVelocity, RandomComponentsInRangeAndKeyedByUid) {
    core::AABB const domain = box(Vec3::Zero(), Vec3(6, 6, 6));
    particles::RandomVelocity rv{-0.1, 0.3, 42};
    auto const g = generateOne(lattice(LatticeKind::SimpleCubic, 1.0, 0.4, domain, rv), domain,
                               {true, true, true});
    ASSERT_EQ(g.size(), 216u);
    Vec3 mean = Vec3::Zero();
    for (auto const& x : g) {
        EXPECT_TRUE((x.velocity.array() >= -0.1).all() && (x.velocity.array() < 0.3).all());
        mean += x.velocity / static_cast<double>(g.size());
        core::random::CounterRng rng(42, x.uid); // the documented draw: x, y, z in order
        double const vx = rng.uniform(-0.1, 0.3);
        double const vy = rng.uniform(-0.1, 0.3);
        double const vz = rng.uniform(-0.1, 0.3);
        EXPECT_EQ(x.velocity, Vec3(vx, vy, vz));
    }
    // Mean of 216 uniforms on [-0.1, 0.3): 0.1 +- 0.0079 (1 sigma) per component.
    EXPECT_LT((mean - Vec3::Constant(0.1)).cwiseAbs().maxCoeff(), 0.04);
    particles::RandomVelocity fixed{0.25, 0.25, 1};
    auto const f = generateOne(lattice(LatticeKind::SimpleCubic, 1.0, 0.4, domain, fixed), domain,
                               {true, true, true});
    EXPECT_EQ(f.front().velocity, Vec3::Constant(0.25));
}
