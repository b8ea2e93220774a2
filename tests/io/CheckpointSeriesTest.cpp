// The checkpoints of a run in its output directory (CheckpointSeries.hpp): names, rotation
// that never touches another run's files, and the earlier run's checkpoints a run will replace.
#include "io/checkpoint/CheckpointSeries.hpp"

#include "core/mpi/Comm.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace regolith;
namespace fs = std::filesystem;

TEST(CheckpointSeries, RotationKeepsTheNewestThisRunWrote) {
    core::Comm const world;
    if (world.rank() != 0)
        return;
    fs::path const dir = fmt::format("checkpoint_rotation_np{}", world.size());
    fs::remove_all(dir);
    fs::create_directories(dir);
    // An earlier run's checkpoints, one of them beyond this run's steps: never touched.
    for (int step : {5, 100})
        std::ofstream(io::checkpointPath(dir.string(), step)) << "x";
    std::ofstream(dir / "notes.txt") << "x";
    EXPECT_EQ(io::checkpointPath("d", 20), (fs::path("d") / "checkpoint_00000020.h5").string());
    std::vector<std::string> written;
    std::vector<std::string> removed;
    for (int step : {10, 20, 30, 40}) {
        written.push_back(io::checkpointPath(dir.string(), step));
        std::ofstream(written.back()) << "x";
        auto const gone = io::rotateCheckpoints(written, 2);
        removed.insert(removed.end(), gone.begin(), gone.end());
        EXPECT_TRUE(fs::exists(io::checkpointPath(dir.string(), step))) << "the newest, " << step;
    }
    EXPECT_EQ(removed, (std::vector<std::string>{io::checkpointPath(dir.string(), 10),
                                                 io::checkpointPath(dir.string(), 20)}));
    EXPECT_EQ(written, (std::vector<std::string>{io::checkpointPath(dir.string(), 30),
                                                 io::checkpointPath(dir.string(), 40)}));
    for (int step : {5, 100})
        EXPECT_TRUE(fs::exists(io::checkpointPath(dir.string(), step)));
    EXPECT_TRUE(fs::exists(dir / "notes.txt"));
    EXPECT_TRUE(io::rotateCheckpoints(written, 0).empty());
    EXPECT_EQ(written.size(), 2U);
}

TEST(CheckpointSeries, ReplacedAreTheEarlierRunsOfThisRunsSteps) {
    core::Comm const world;
    if (world.rank() != 0)
        return;
    fs::path const dir = fmt::format("checkpoint_replaced_np{}", world.size());
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (int step : {5, 10, 20, 25, 30, 60})
        std::ofstream(io::checkpointPath(dir.string(), step)) << "x";
    std::ofstream(dir / "checkpoint_x.h5") << "x";
    std::ofstream(dir / "checkpoint_00000040.h5.tmp") << "x";
    // Every 10 steps after step 10 up to 50: 20 and 30 (not 10, the start; not 25, not 60).
    EXPECT_EQ(io::checkpointsToReplace(dir.string(), 10, 10, 50),
              (std::vector<std::string>{"checkpoint_00000020.h5", "checkpoint_00000030.h5"}));
    EXPECT_TRUE(io::checkpointsToReplace(dir.string(), 0, 0, 50).empty());
    EXPECT_TRUE(io::checkpointsToReplace((dir / "absent").string(), 10, 0, 50).empty());
}
