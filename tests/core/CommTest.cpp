// Communicator wrapper: reductions, gathers, duplication.
#include "core/mpi/Comm.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace regolith::core;

TEST(Comm, ReductionsAgreeWithClosedForms) {
    Comm world;
    int const p = world.size();
    EXPECT_EQ(world.allReduce(world.rank() + 1, ReduceOp::Sum), p * (p + 1) / 2);
    EXPECT_EQ(world.allReduce(world.rank(), ReduceOp::Max), p - 1);
    EXPECT_EQ(world.allReduce(world.rank(), ReduceOp::Min), 0);
    EXPECT_FALSE(world.allTrue(world.rank() != p - 1));
    EXPECT_TRUE(world.allTrue(true));
}

TEST(Comm, DuplicateHasSameGroupAndIsIndependent) {
    Comm world;
    Comm dup = world.duplicate();
    EXPECT_EQ(dup.rank(), world.rank());
    EXPECT_EQ(dup.size(), world.size());
    EXPECT_NE(dup.raw(), world.raw());
    Comm moved = std::move(dup);
    EXPECT_EQ(moved.allReduce(1, ReduceOp::Sum), world.size());
}

TEST(Comm, GatherAndBroadcastStrings) {
    Comm world;
    auto const all =
        world.gatherStrings(std::string(static_cast<std::size_t>(world.rank()), 'r'), 0);
    if (world.rank() == 0) {
        ASSERT_EQ(static_cast<int>(all.size()), world.size());
        for (int r = 0; r < world.size(); ++r)
            EXPECT_EQ(all[static_cast<std::size_t>(r)].size(), static_cast<std::size_t>(r));
    }
    std::string s = world.rank() == 0 ? "from root" : "";
    world.broadcast(s, 0);
    EXPECT_EQ(s, "from root");
}
