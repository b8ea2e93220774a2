// The memory pre-check: what every rank of a node needs at once, against the node's memory.
#include "core/memory/MemoryBudget.hpp"

#include "core/Error.hpp"
#include "core/mpi/Comm.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace regolith;

TEST(MemoryBudget, ComparesWhatTheRanksOfANodeNeedWithTheNode) {
    core::Comm const world;
    double const node = static_cast<double>(core::physicalMemoryBytes());
    if (node == 0.0)
        GTEST_SKIP() << "the machine's memory is unknown";
    // The tests run every rank on this one machine.
    EXPECT_EQ(core::ranksPerNode(), world.size());
    // 0.6 of the node per rank: fits one rank, not two on the node.
    double const share = 0.6 * node;
    if (world.size() == 1) {
        EXPECT_NO_THROW(core::requireMemory(share, "particles[0].count", "an agglomerate"));
        return;
    }
    try {
        core::requireMemory(share, "particles[0].count", "an agglomerate");
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        std::string const what = e.what();
        EXPECT_EQ(what.rfind("particles[0].count: an agglomerate needs about ", 0), 0U) << what;
        EXPECT_NE(what.find(" GiB for the " + std::to_string(world.size()) + " ranks on a node"),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find("; change particles[0].count, or run fewer ranks per node"),
                  std::string::npos)
            << what;
    }
    // A need that fits the node with every rank on it passes.
    EXPECT_NO_THROW(
        core::requireMemory(0.5 * node / world.size(), "particles[0].count", "an agglomerate"));
}
