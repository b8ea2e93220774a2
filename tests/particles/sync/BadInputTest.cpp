// Bad input: a grain inserted twice with the same uid is refused on every rank with one clear
// message; a synchronisation message cut short is detected by the bounds-checked buffer (a
// core::BufferError naming what was being read), never read past its end; a grain whose
// position became non-finite (an unstable step) stops the run, naming it.
#include "core/Error.hpp"
#include "particles/sync/ParticleSync.hpp"
#include "particles/sync/SyncMessages.hpp"
#include "particles/sync/UniqueUids.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <fmt/format.h>

#include <limits>
#include <string>

using namespace regolith::particles;
using namespace regolith::particles::synctest;
using regolith::core::BufferError;
using regolith::core::InputError;

namespace {

/// 4x2x2 blocks of edge 4: every rank of up to 8 owns at least one block.
domain::ForestSpec sixteenBlocks() {
    return forestSpec(Vec3::Zero(), Vec3(16, 8, 8), {4, 2, 2}, allAxes(false));
}

std::string verdict(LocalParticles const& local, Comm const& comm) {
    try {
        verifyUniqueMasters(local, comm);
    } catch (InputError const& e) {
        return e.what();
    }
    return {};
}

std::string at(Vec3 const& x) {
    return fmt::format("({:.17g}, {:.17g}, {:.17g})", x[0], x[1], x[2]);
}

/// Centre of this rank's `k`-th block (of the last one if it has fewer).
Vec3 blockCentre(LocalParticles const& local, std::size_t k) {
    auto const blocks = local.forest().blocks();
    return blocks[std::min(k, blocks.size() - 1)].aabb.center();
}

} // namespace

TEST(UniqueMasters, DistinctUidsPass) {
    Comm world;
    domain::BlockForest const forest(world, sixteenBlocks());
    LocalParticles local(forest);
    addAll(local, world, randomGas(forest.domain(), 500, 0.1, 0.2, 1.0, 2));
    EXPECT_EQ(verdict(local, world), "");
}

TEST(UniqueMasters, SameUidOnTwoRanksIsRefusedEverywhere) {
    Comm world;
    domain::BlockForest const forest(world, sixteenBlocks());
    LocalParticles local(forest);
    addAll(local, world, randomGas(forest.domain(), 200, 0.1, 0.2, 1.0, 2));
    // The first and the last rank insert the same uid, each in one of its blocks (one rank:
    // in two of its blocks).
    Uid const twice = makeUid(0, 7);
    int const last = world.size() - 1;
    for (BlockParticles& bp : local.blocks()) // make room: the gas may hold uid `twice`
        bp.particles.removeUid(twice);
    std::array<double, 6> xs{0, 0, 0, 0, 0, 0};
    if (world.rank() == 0) {
        Vec3 const a = blockCentre(local, 0);
        EXPECT_TRUE(local.addMaster(grain(twice, a, 0.1)));
        xs = {a[0], a[1], a[2], 0, 0, 0};
    }
    if (world.rank() == last) {
        Vec3 const b = blockCentre(local, 1);
        EXPECT_TRUE(local.addMaster(grain(twice, b, 0.1)));
        xs[3] = b[0];
        xs[4] = b[1];
        xs[5] = b[2];
    }
    world.allReduceInPlace(std::span<double>(xs), regolith::core::ReduceOp::Sum);
    std::string const msg = verdict(local, world);
    EXPECT_NE(msg.find("uid " + std::to_string(twice)), std::string::npos) << msg;
    EXPECT_NE(msg.find("a grain inserted twice with the same uid"), std::string::npos) << msg;
    EXPECT_NE(msg.find(at(Vec3(xs[0], xs[1], xs[2]))), std::string::npos) << msg;
    EXPECT_NE(msg.find(at(Vec3(xs[3], xs[4], xs[5]))), std::string::npos) << msg;
    EXPECT_EQ(msg.find("more uids"), std::string::npos) << msg;
    for (std::string const& s : world.gatherStrings(msg, 0)) // the same text on every rank
        EXPECT_EQ(s, msg);
}

TEST(UniqueMasters, NamesTheSmallestOfSeveralDuplicates) {
    Comm world;
    domain::BlockForest const forest(world, sixteenBlocks());
    LocalParticles local(forest);
    // Every rank inserts uids (1, 5), (1, 9) and (2, 3) in its first block: duplicated as soon
    // as there are two ranks; with one rank, its last block repeats them.
    std::vector<Uid> const uids{makeUid(1, 9), makeUid(2, 3), makeUid(1, 5)};
    for (Uid u : uids)
        EXPECT_TRUE(local.addMaster(grain(u, blockCentre(local, 0), 0.1)));
    if (world.size() == 1) {
        for (Uid u : uids)
            EXPECT_TRUE(local.addMaster(grain(u, blockCentre(local, 15), 0.1)));
    }
    std::string const msg = verdict(local, world);
    EXPECT_NE(msg.find("uid " + std::to_string(makeUid(1, 5)) + " "), std::string::npos) << msg;
    EXPECT_NE(msg.find("(2 more uids are duplicated)"), std::string::npos) << msg;
    for (std::string const& s : world.gatherStrings(msg, 0))
        EXPECT_EQ(s, msg);
}

// A full-state record (create / promote) cut at every length: every cut is reported as a
// short or corrupt buffer; the whole record reads back what was written.
TEST(TruncatedMessage, EveryCutOfAParticleRecordIsDetected) {
    using namespace regolith::particles::sync_detail;
    ParticleStorage ps;
    ParticleInit p = grain(makeUid(2, 11), Vec3(1.5, -2.25, 3.125), 0.75, Vec3(0.1, 0.2, 0.3));
    p.owner = BlockRef{3, 77};
    std::size_t const i = ps.add(p);
    ps.history(i).set(HistoryEntry{makeUid(1, 4), Vec3(0.01, 0.02, 0.03), 5});
    ps.history(i).set(HistoryEntry{makeUid(1, 6), Vec3(-0.01, 0.0, 0.5), 5});
    ps.force(i) = Vec3(7, 8, 9);
    std::vector<CopyRef> const holders{{0, 12, {0, 0, 1}}, {1, 13, kNoImage}};
    regolith::core::SendBuffer out;
    writeHeader(out, RecordKind::Promote, 77);
    writeFull(out, ps, i, ps.position(i), kNoImage, p.owner, holders);
    std::vector<std::byte> const bytes(out.bytes().begin(), out.bytes().end());

    auto read = [](std::vector<std::byte> data) {
        regolith::core::RecvBuffer in(std::move(data));
        RecordKind kind{};
        std::uint64_t block = 0;
        in >> kind >> block;
        FullState s = readFull(in);
        EXPECT_TRUE(in.exhausted());
        return s;
    };
    FullState const whole = read(bytes);
    EXPECT_EQ(whole.init.uid, p.uid);
    EXPECT_TRUE(sameBits(whole.init.position, p.position));
    EXPECT_TRUE(sameBits(whole.init.force, Vec3(7, 8, 9)));
    EXPECT_EQ(whole.history.size(), 2U);
    EXPECT_EQ(whole.holders, holders);

    std::size_t detected = 0;
    for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
        std::vector<std::byte> const part(bytes.begin(),
                                          bytes.begin() + static_cast<std::ptrdiff_t>(cut));
        try {
            (void)read(part);
            ADD_FAILURE() << "a record cut to " << cut << " of " << bytes.size()
                          << " bytes was read without error";
        } catch (BufferError const& e) {
            std::string const m = e.what();
            bool const clear =
                m.find("too short") != std::string::npos || m.find("corrupt") != std::string::npos;
            EXPECT_TRUE(clear) << m;
            ++detected;
        }
    }
    EXPECT_EQ(detected, bytes.size());
}

// A count field overwritten with garbage (a corrupt, not a short, buffer) is caught before
// anything is allocated for it.
TEST(TruncatedMessage, CorruptCountIsDetected) {
    using namespace regolith::particles::sync_detail;
    ParticleStorage ps;
    std::size_t const i = ps.add(grain(makeUid(0, 1), Vec3(1, 2, 3), 0.5));
    regolith::core::SendBuffer out;
    writeFull(out, ps, i, ps.position(i), kNoImage, BlockRef{0, 1}, {});
    std::vector<std::byte> bytes(out.bytes().begin(), out.bytes().end());
    // The history count sits 8 + 8 bytes before the end (history count, then holders count).
    std::uint64_t const huge = std::uint64_t{1} << 60;
    std::memcpy(bytes.data() + bytes.size() - 16, &huge, sizeof huge);
    regolith::core::RecvBuffer in(std::move(bytes));
    try {
        (void)readFull(in);
        ADD_FAILURE() << "a corrupt history count was accepted";
    } catch (BufferError const& e) {
        EXPECT_NE(std::string(e.what()).find("corrupt"), std::string::npos) << e.what();
    }
}

TEST(NonFinitePosition, StopsTheSynchronisationNamingTheGrain) {
    // Periodic on every axis: there is no open face to leave through. Every rank spoils one of
    // its masters, so every rank throws before any message (none waits for another).
    Comm world;
    domain::BlockForest const forest(
        world, forestSpec(Vec3::Zero(), Vec3(16, 8, 8), {4, 2, 2}, allAxes(true)));
    for (SyncMethod const method :
         {SyncMethod::NextNeighbour, SyncMethod::ShadowOwner, SyncMethod::Hybrid}) {
        LocalParticles local(forest);
        addAll(local, world, randomGas(forest.domain(), 300, 0.1, 0.2, 1.0, 3));
        ParticleSync sync(world, forest, SyncConfig{method, false});
        sync.syncUntilConverged(local);
        ParticleStorage* spoilt = nullptr;
        for (BlockParticles& bp : local.blocks())
            if (spoilt == nullptr && !bp.particles.empty())
                spoilt = &bp.particles;
        ASSERT_NE(spoilt, nullptr) << "the gas fills every block";
        std::size_t k = 0;
        while (!spoilt->flags(k).isMaster())
            ++k;
        Uid const uid = spoilt->uid(k);
        spoilt->position(k).x() = std::numeric_limits<double>::infinity();
        try {
            sync.sync(local);
            ADD_FAILURE() << "a grain at infinity was synchronised";
        } catch (regolith::core::Error const& e) {
            std::string const msg = e.what();
            EXPECT_NE(msg.find("uid " + std::to_string(uid) + " has a non-finite position"),
                      std::string::npos)
                << msg;
        }
    }
}
