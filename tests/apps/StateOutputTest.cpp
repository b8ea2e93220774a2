// The state outputs of the apps: the checksum and the dump depend on the global set of
// masters only (not on the rank count, the distribution or the local order), the checksum
// sees every changed bit and every lost or doubled master, the dump has the contract's format,
// and the conserved quantities match hand-computed values.
#include "apps/common/ConservedQuantities.hpp"
#include "apps/common/StateChecksum.hpp"
#include "apps/common/StateDump.hpp"
#include "core/mpi/Comm.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using namespace regolith;
using apps::MasterRecord;
using core::Comm;
using core::Vec3;

namespace {

constexpr int kMasters = 57;

/// A fixed global state with irregular values and uids out of order.
std::vector<MasterRecord> globalState() {
    std::vector<MasterRecord> all;
    for (int i = 0; i < kMasters; ++i) {
        double const t = 0.37 * i + 0.1;
        MasterRecord m;
        m.uid = static_cast<std::uint64_t>((i * 7919) % 1009) + 1000;
        m.position = Vec3(std::sin(t) * 3.0, std::cos(t), t / 7.0);
        m.velocity = Vec3(1e-3 * i, -0.25 * std::sin(3 * t), 0.0);
        m.angularVelocity = Vec3(0.0, 0.0, i % 3 == 0 ? 1.5 : 0.0);
        m.radius = 0.1 + 0.01 * (i % 5);
        m.mass = 4.0 / 3.0 * std::numbers::pi * std::pow(m.radius, 3) * 2.5;
        all.push_back(m);
    }
    return all;
}

/// Round robin, in storage order.
std::vector<MasterRecord> roundRobin(Comm const& world, std::vector<MasterRecord> const& all) {
    std::vector<MasterRecord> mine;
    for (std::size_t i = 0; i < all.size(); ++i)
        if (static_cast<int>(i % static_cast<std::size_t>(world.size())) == world.rank())
            mine.push_back(all[i]);
    return mine;
}

/// Contiguous chunks of very different sizes, each in reverse order.
std::vector<MasterRecord> skewedChunks(Comm const& world, std::vector<MasterRecord> const& all) {
    std::vector<MasterRecord> mine;
    auto const p = static_cast<std::size_t>(world.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
        // rank of i: quadratic cut points, so the last rank holds the most.
        std::size_t r = 0;
        while (r + 1 < p && (r + 1) * (r + 1) * all.size() <= i * p * p)
            ++r;
        if (static_cast<int>(r) == world.rank())
            mine.push_back(all[i]);
    }
    std::reverse(mine.begin(), mine.end());
    return mine;
}

/// Every master on rank 0 alone (what one rank would hold).
std::string serialChecksum(std::vector<MasterRecord> const& all) {
    Comm self(MPI_COMM_SELF);
    return apps::stateChecksum(self, all);
}

} // namespace

TEST(StateChecksum, IndependentOfDistributionAndOrder) {
    Comm world;
    auto const all = globalState();
    std::string const expected = serialChecksum(all);
    EXPECT_EQ(expected.size(), 16u);
    EXPECT_EQ(apps::stateChecksum(world, roundRobin(world, all)), expected);
    EXPECT_EQ(apps::stateChecksum(world, skewedChunks(world, all)), expected);
    // Everything on the last rank, nothing elsewhere.
    std::vector<MasterRecord> const lastOnly =
        world.rank() == world.size() - 1 ? all : std::vector<MasterRecord>{};
    EXPECT_EQ(apps::stateChecksum(world, lastOnly), expected);
}

TEST(StateChecksum, SeesOneFlippedBitAnywhere) {
    Comm world;
    auto const all = globalState();
    std::string const reference = serialChecksum(all);
    // Flip the lowest mantissa bit of each field of one master in turn, and the uid's low bit.
    for (int field = 0; field < 12; ++field) {
        auto changed = all;
        MasterRecord& m = changed[17];
        auto flip = [](double& x) {
            x = std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) ^ 1U);
        };
        if (field == 0)
            m.uid ^= 1U;
        else if (field <= 3)
            flip(m.position[field - 1]);
        else if (field <= 6)
            flip(m.velocity[field - 4]);
        else if (field <= 9)
            flip(m.angularVelocity[field - 7]);
        else if (field == 10)
            flip(m.radius);
        else
            flip(m.mass);
        EXPECT_NE(apps::stateChecksum(world, roundRobin(world, changed)), reference)
            << "field " << field;
    }
    auto signedZero = all;
    signedZero[3].velocity.z() = -0.0; // bitwise different state, numerically equal
    EXPECT_NE(apps::stateChecksum(world, roundRobin(world, signedZero)), reference);
}

TEST(StateChecksum, SeesALostOrDoubledMaster) {
    Comm world;
    auto const all = globalState();
    std::string const reference = serialChecksum(all);
    auto lost = all;
    lost.erase(lost.begin() + 30);
    EXPECT_NE(apps::stateChecksum(world, roundRobin(world, lost)), reference);
    // The same master on two ranks (a shadow counted as a master).
    auto mine = roundRobin(world, all);
    if (world.rank() == world.size() - 1)
        mine.push_back(all[0]);
    EXPECT_NE(apps::stateChecksum(world, mine), reference);
    // Two masters swapping their states but not their uids.
    auto swapped = all;
    std::swap(swapped[4].position, swapped[5].position);
    EXPECT_NE(apps::stateChecksum(world, roundRobin(world, swapped)), reference);
}

TEST(StateDump, SameBytesForEveryDistributionOnRankZeroOnly) {
    Comm world;
    auto const all = globalState();
    std::string const expected = apps::dumpCsv(all);
    std::string const a = apps::gatherDumpCsv(world, roundRobin(world, all));
    std::string const b = apps::gatherDumpCsv(world, skewedChunks(world, all));
    if (world.rank() == 0) {
        EXPECT_EQ(a, expected);
        EXPECT_EQ(b, expected);
    } else {
        EXPECT_EQ(a, "");
        EXPECT_EQ(b, "");
    }
}

TEST(StateDump, FormatSortedByUidWithRoundTripDigits) {
    auto const all = globalState();
    std::istringstream in(apps::dumpCsv(all));
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line + "\n", apps::dumpHeader());
    // The dump contract (docs/design.md, "Dump"), which `kind = "file"` sources read back.
    EXPECT_EQ(apps::dumpHeader(), "uid,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass\n");
    std::vector<MasterRecord> read;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::string f;
        std::vector<std::string> cols;
        while (std::getline(fields, f, ','))
            cols.push_back(f);
        ASSERT_EQ(cols.size(), 12u) << line;
        MasterRecord m;
        m.uid = std::stoull(cols[0]);
        for (int a = 0; a < 3; ++a) {
            auto const ua = static_cast<std::size_t>(a);
            m.position[a] = std::stod(cols[1 + ua]);
            m.velocity[a] = std::stod(cols[4 + ua]);
            m.angularVelocity[a] = std::stod(cols[7 + ua]);
        }
        m.radius = std::stod(cols[10]);
        m.mass = std::stod(cols[11]);
        read.push_back(m);
    }
    ASSERT_EQ(read.size(), all.size());
    EXPECT_TRUE(std::is_sorted(read.begin(), read.end(),
                               [](auto const& x, auto const& y) { return x.uid < y.uid; }));
    // 17 significant digits read back to the same doubles: the same checksum.
    EXPECT_EQ(serialChecksum(read), serialChecksum(all));
    // One line spelled out: shortest exact forms are not used, 17 digits are.
    MasterRecord m;
    m.uid = 42;
    m.position = Vec3(0.1, -2.0, 1e-20);
    m.velocity = Vec3(0.0, -0.0, 3.0);
    m.radius = 0.4;
    m.mass = 1.0 / 3.0;
    std::vector<MasterRecord> const one{m};
    EXPECT_EQ(apps::dumpCsv(one),
              std::string(apps::dumpHeader()) +
                  "42,0.10000000000000001,-2,9.9999999999999995e-21,0,-0,3,0,0,0,"
                  "0.40000000000000002,0.33333333333333331\n");
}

TEST(StateDump, EmptyStateIsTheHeaderOnly) {
    Comm world;
    std::string const text = apps::gatherDumpCsv(world, {});
    EXPECT_EQ(text, world.rank() == 0 ? std::string(apps::dumpHeader()) : std::string());
}

TEST(ConservedQuantities, HandComputedTwoGrainState) {
    Comm world;
    MasterRecord a;
    a.uid = 1;
    a.position = Vec3(0, 1, 0);
    a.velocity = Vec3(1, 0, 0);
    a.radius = 0.5;
    a.mass = 2.0;
    MasterRecord b;
    b.uid = 2;
    b.position = Vec3(2, 0, 3);
    b.angularVelocity = Vec3(0, 0, 2);
    b.radius = 1.0;
    b.mass = 1.0;
    // a on rank 0, b on the last rank (the same rank on one rank).
    std::vector<MasterRecord> mine;
    if (world.rank() == 0)
        mine.push_back(a);
    if (world.rank() == world.size() - 1)
        mine.push_back(b);
    auto const c = apps::conservedQuantities(world, mine, Vec3(0, 0, -10));
    // p = 2 (1,0,0); L = (0,1,0) x (2,0,0) + 2/5 * 1 * 1^2 * (0,0,2) = (0,0,-2) + (0,0,0.8);
    // K = 1/2 2 1 + 1/2 0.4 4 = 1.8; U = -sum m g.x = 1 * 10 * 3 = 30; com = (2,2,3)/3.
    EXPECT_EQ(c.momentum, Vec3(2, 0, 0));
    EXPECT_NEAR((c.angularMomentum - Vec3(0, 0, -1.2)).norm(), 0.0, 1e-15);
    EXPECT_NEAR(c.kineticEnergy, 1.8, 1e-15);
    EXPECT_NEAR(c.potentialEnergy, 30.0, 1e-14);
    EXPECT_NEAR((c.centerOfMass - Vec3(2.0 / 3.0, 2.0 / 3.0, 1.0)).norm(), 0.0, 1e-15);
    auto const none = apps::conservedQuantities(world, {}, Vec3(0, 0, -10));
    EXPECT_EQ(none.centerOfMass, Vec3::Zero());
    EXPECT_EQ(none.kineticEnergy, 0.0);
}
