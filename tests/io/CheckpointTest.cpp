// HDF5 checkpoints (io/checkpoint): every stored field of every master, contact history
// included, survives a write and a read bit for bit, also when a sub-communicator of another
// size reads what all ranks wrote; the write leaves no temporary behind and writes through no
// link. Damaged and foreign files are refused in CheckpointRefusalTest.cpp.
#include "core/Error.hpp"
#include "domain/BlockForest.hpp"
#include "io/checkpoint/CheckpointReader.hpp"
#include "io/checkpoint/CheckpointWriter.hpp"
#include "io/checkpoint/RestoreGrains.hpp"
#include "tests/io/CheckpointSample.hpp"
#include "tests/io/DatasetText.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace regolith;
using namespace regolith::checkpointtest;
using core::Vec3;
namespace fs = std::filesystem;

namespace {

std::vector<io::GrainState> sortedMasters(particles::LocalParticles const& local) {
    auto out = io::collectMasters(local);
    std::sort(out.begin(), out.end(), [](auto const& a, auto const& b) { return a.uid < b.uid; });
    return out;
}

/// Equal in every bit of every field (the hashes cover every stored field).
void expectSame(std::vector<io::GrainState> const& a, std::vector<io::GrainState> const& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].uid, b[i].uid);
        EXPECT_EQ(io::grainHash(a[i]), io::grainHash(b[i])) << "uid " << a[i].uid;
        EXPECT_EQ(a[i].history.size(), b[i].history.size());
    }
}

} // namespace

TEST(Checkpoint, RoundTripIsBitwise) {
    core::Comm const world;
    std::string const path = fileName(world, "roundtrip");
    writeSample(world, path);
    domain::BlockForest const forest(world, spec());
    auto const expected = sortedMasters(fill(forest));
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    EXPECT_EQ(slice.info.step, 20);
    EXPECT_EQ(slice.info.time, 0.2);
    EXPECT_EQ(slice.info.scene, info().scene);
    EXPECT_EQ(slice.info.stateChecksum, info().stateChecksum);
    EXPECT_EQ(slice.info.historyCount, 33U); // 11 grains with one entry, 11 with two
    particles::LocalParticles restored(forest);
    io::restoreGrains(world, restored, slice.grains, "test");
    expectSame(expected, sortedMasters(restored));
    // Every flag byte as written, the synchronisation class included.
    std::vector<io::GrainState> const written = allGrains();
    for (io::GrainState const& g : sortedMasters(restored)) {
        auto const it = std::find_if(written.begin(), written.end(),
                                     [&](io::GrainState const& w) { return w.uid == g.uid; });
        ASSERT_NE(it, written.end());
        EXPECT_EQ(int{g.flags.bits()}, int{it->flags.bits()}) << "uid " << g.uid;
    }
}

TEST(Checkpoint, DatasetsCarryUnitsAndDescription) {
    using test::datasetText;
    core::Comm const world;
    std::string const path = fileName(world, "attributes");
    writeSample(world, path);
    world.barrier();
    EXPECT_EQ(datasetText(path, "position", "units"), "length");
    EXPECT_EQ(datasetText(path, "velocity", "units"), "length/time");
    EXPECT_EQ(datasetText(path, "force", "units"), "mass length/time^2");
    EXPECT_EQ(datasetText(path, "uid", "units"), "1");
    EXPECT_EQ(datasetText(path, "mass", "description"), "mass");
    // Every dataset has both (a file with grains and contact history: all columns written).
    for (char const* set :
         {"uid", "position", "velocity", "angular_velocity", "orientation", "force", "torque",
          "radius", "mass", "type", "flags", "gravity_reference", "gravity_field", "gravity_slope",
          "history_offset", "history_count", "history_partner", "history_spring",
          "history_stamp"}) {
        EXPECT_FALSE(datasetText(path, set, "units").empty()) << set;
        EXPECT_FALSE(datasetText(path, set, "description").empty()) << set;
    }
}

TEST(Checkpoint, SceneTextBeyond64KiBRoundTrips) {
    // A scene listing a few thousand grains: an HDF5 attribute in the object header stops at
    // 64 KiB, and the write failed (the run aborted at its first checkpoint).
    core::Comm const world;
    std::string const path = fileName(world, "large_scene");
    domain::BlockForest const forest(world, spec());
    auto const grains = io::collectMasters(fill(forest));
    io::CheckpointInfo written = info();
    for (int k = 0; written.scene.size() < 200'000; ++k)
        written.scene += fmt::format("  [{}.0, 1.5, 2.5],\n", k);
    io::writeCheckpoint(world, path, written, grains);
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    EXPECT_EQ(slice.info.scene, written.scene);
    EXPECT_EQ(slice.info.grainCount, 64U);
}

TEST(Checkpoint, FailedRenameLeavesNoTemporary) {
    // A directory where the checkpoint goes: the rename fails, every rank gets the error, and
    // the temporary is removed (it stayed behind, a full-size file per failed checkpoint).
    core::Comm const world;
    std::string const path = fileName(world, "blocked");
    if (world.rank() == 0) {
        fs::remove_all(path);
        fs::create_directories(path + "/x");
    }
    world.barrier();
    domain::BlockForest const forest(world, spec());
    io::CheckpointInfo written = info();
    try {
        io::writeCheckpoint(world, path, written, io::collectMasters(fill(forest)));
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find("renaming '" + path + ".tmp"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(hasTemporary(path));
    world.barrier();
    if (world.rank() == 0)
        fs::remove_all(path);
}

TEST(Checkpoint, LeftoverTemporaryLinkIsNotWrittenThrough) {
    // Links where a temporary would go (the name written before, and the one rank 0's process
    // takes first): their target keeps its content, and the checkpoint is a file of its own.
    core::Comm const world;
    std::string const path = fileName(world, "leftover");
    std::string const victim = fileName(world, "victim");
    long const pid = world.allReduce(world.rank() == 0 ? static_cast<long>(::getpid()) : 0L,
                                     core::ReduceOp::Sum);
    std::vector<std::string> const links{path + ".tmp", fmt::format("{}.tmp{}", path, pid)};
    if (world.rank() == 0) {
        fs::remove(path);
        std::ofstream(victim) << "keep";
        for (std::string const& link : links) {
            fs::remove(link);
            fs::create_symlink(victim, link);
        }
    }
    world.barrier();
    domain::BlockForest const forest(world, spec());
    io::CheckpointInfo written = info();
    io::writeCheckpoint(world, path, written, io::collectMasters(fill(forest)));
    world.barrier();
    std::ifstream in(victim);
    std::string content;
    std::getline(in, content);
    EXPECT_EQ(content, "keep");
    EXPECT_FALSE(fs::is_symlink(path));
    EXPECT_EQ(io::readCheckpoint(world, path).info.grainCount, 64U);
    for (std::string const& link : links)
        EXPECT_TRUE(fs::is_symlink(link)) << link; // not the writer's to remove
    world.barrier();
    if (world.rank() == 0) {
        for (std::string const& link : links)
            fs::remove(link);
        fs::remove(victim);
        fs::remove(path);
    }
}

TEST(Checkpoint, SelfGravityStateSurvivesBitForBit) {
    // The self-gravity state (format 2): per grain its reference position and cached field
    // (NaN rows for grains without one), and the run-wide update count and energy. Each rank
    // writes every P-th grain; the slices read back hash equal to what was written.
    core::Comm const world;
    std::string const path = fileName(world, "gravity");
    std::vector<io::GrainState> all = allGrains();
    for (std::size_t k = 0; k < all.size(); ++k)
        if (k % 4 != 3) {
            all[k].gravityReference = all[k].position + Vec3(1e-3, -0.0, 1.0 / 3.0);
            all[k].gravityField = Vec3(-1e-7 * static_cast<double>(k), 2.5e-300, -0.0);
        }
    std::vector<io::GrainState> mine;
    for (std::size_t k = static_cast<std::size_t>(world.rank()); k < all.size();
         k += static_cast<std::size_t>(world.size()))
        mine.push_back(all[k]);
    io::CheckpointInfo i = info();
    i.gravityUpdates = 17;
    i.gravityPotentialEnergy = -1.0 / 3.0;
    (void)io::writeCheckpoint(world, path, i, mine);
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    EXPECT_EQ(slice.info.gravityUpdates, 17);
    EXPECT_EQ(slice.info.gravityPotentialEnergy, -1.0 / 3.0);
    long long found = 0;
    for (io::GrainState const& g : slice.grains) {
        auto const it = std::find_if(all.begin(), all.end(),
                                     [&](io::GrainState const& a) { return a.uid == g.uid; });
        ASSERT_NE(it, all.end());
        EXPECT_EQ(io::grainHash(*it), io::grainHash(g)) << "uid " << g.uid;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(g.gravityField.z()),
                  std::bit_cast<std::uint64_t>(it->gravityField.z()));
        EXPECT_EQ(std::isnan(g.gravityReference.x()), std::isnan(it->gravityReference.x()));
        ++found;
    }
    EXPECT_EQ(world.allReduce(found, core::ReduceOp::Sum), 64);
}

TEST(Checkpoint, OtherRankCountReadsTheSameGrains) {
    // What all ranks wrote, read back by ranks 0 and 1 only (or rank 0 alone on one rank).
    core::Comm const world;
    std::string const path = fileName(world, "subset");
    writeSample(world, path);
    MPI_Comm half = MPI_COMM_NULL;
    MPI_Comm_split(world.raw(), world.rank() < 2 ? 0 : 1, world.rank(), &half);
    {
        core::Comm const sub(half);
        domain::BlockForest const forest(sub, spec());
        io::CheckpointSlice const slice = io::readCheckpoint(sub, path);
        particles::LocalParticles restored(forest);
        io::restoreGrains(sub, restored, slice.grains, "test");
        auto const count =
            sub.allReduce(static_cast<long long>(restored.countMasters()), core::ReduceOp::Sum);
        EXPECT_EQ(count, 64);
        expectSame(sortedMasters(fill(forest)), sortedMasters(restored));
    }
    MPI_Comm_free(&half);
}

TEST(Checkpoint, IdleRanksWriteAndReadNothing) {
    // Two blocks: on 4 ranks two ranks own no block and no grain, yet join every collective.
    core::Comm const world;
    domain::ForestSpec s = spec();
    s.rootBlocks = {2, 1, 1};
    domain::BlockForest const forest(world, s);
    particles::LocalParticles local(forest);
    for (io::GrainState const& g : allGrains())
        (void)local.addMaster(io::toParticleInit(g));
    std::string const path = fileName(world, "idle");
    io::CheckpointInfo i = info();
    io::writeCheckpoint(world, path, i, io::collectMasters(local));
    EXPECT_EQ(i.grainCount, 64U);
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    particles::LocalParticles restored(forest);
    io::restoreGrains(world, restored, slice.grains, "test");
    EXPECT_EQ(restored.countMasters(), local.countMasters());
    EXPECT_EQ(world.allReduce(static_cast<long long>(restored.countMasters()), core::ReduceOp::Sum),
              64);
}
