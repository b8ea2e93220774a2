// Bad [domain] input: core::InputError whose message names the scene key and the value.
#include "domain/SpecValidation.hpp"

#include "core/Error.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

using namespace regolith;
using namespace regolith::domain;

namespace {

ForestSpec good() {
    ForestSpec s;
    s.domain = {core::Vec3(0, 0, 0), core::Vec3(4, 4, 4)};
    s.rootBlocks = {4, 4, 4};
    return s;
}

/// Expects `spec` to be rejected, by validate() and by the forest, with a message holding
/// every string in `parts`.
void expectRejected(ForestSpec const& spec, std::vector<std::string> const& parts) {
    for (int how = 0; how < 2; ++how) {
        try {
            if (how == 0) {
                validate(spec);
            } else {
                core::Comm world;
                BlockForest const forest(world, spec);
            }
            ADD_FAILURE() << "accepted; expected an error mentioning " << parts.front();
        } catch (core::InputError const& e) {
            std::string const what = e.what();
            for (std::string const& p : parts)
                EXPECT_NE(what.find(p), std::string::npos) << "'" << p << "' not in: " << what;
        }
    }
}

} // namespace

TEST(SpecValidation, AcceptsAValidSpec) {
    ForestSpec s = good();
    s.refine.push_back({{core::Vec3(0, 0, 0), core::Vec3(4, 4, 4)}, kMaxRefineLevel});
    s.refine.push_back({{core::Vec3(1, 1, 1), core::Vec3(1, 1, 1)}, 0});
    s.cellsPerBlock = {8, 8, 8};
    EXPECT_NO_THROW(validate(s));
}

TEST(SpecValidation, RejectsEmptyOrNonFiniteExtent) {
    ForestSpec s = good();
    s.domain.max = core::Vec3(4, 0, 4);
    expectRejected(s, {"domain.max", "max > min", "[4, 0, 4]"});
    s.domain.max = core::Vec3(-1, 4, 4);
    expectRejected(s, {"domain.max", "[-1, 4, 4]"});
    s = good();
    s.domain.min[1] = std::numeric_limits<double>::quiet_NaN();
    expectRejected(s, {"domain.min", "finite"});
    s = good();
    s.domain.max[2] = std::numeric_limits<double>::infinity();
    expectRejected(s, {"domain.max", "finite"});
}

TEST(SpecValidation, RejectsNonPositiveOrTooManyBlocks) {
    ForestSpec s = good();
    s.rootBlocks = {4, 0, 4};
    expectRejected(s, {"domain.blocks: expected positive integers, got [4, 0, 4]"});
    s.rootBlocks = {-2, 1, 1};
    expectRejected(s, {"domain.blocks", "[-2, 1, 1]"});
    s.rootBlocks = {kMaxRootBlocksPerAxis + 1, 1, 1};
    expectRejected(s, {"domain.blocks", "per axis"});
    s.rootBlocks = {1024, 1024, 1024};
    expectRejected(s, {"domain.blocks", "in total"});
}

TEST(SpecValidation, RejectsRefineLevelOutOfRange) {
    ForestSpec s = good();
    s.refine.push_back({{core::Vec3(0, 0, 0), core::Vec3(1, 1, 1)}, 1});
    s.refine.push_back({{core::Vec3(0, 0, 0), core::Vec3(1, 1, 1)}, kMaxRefineLevel + 1});
    expectRejected(s, {"domain.refine[1].level", "[0, 8]", "got 9"});
    s.refine[1].level = -1;
    expectRejected(s, {"domain.refine[1].level", "got -1"});
}

TEST(SpecValidation, RejectsRefineRegionOutsideTheDomain) {
    ForestSpec s = good();
    s.refine.push_back({{core::Vec3(3, 3, 3), core::Vec3(5, 3.5, 3.5)}, 1});
    expectRejected(s, {"domain.refine[0].region", "inside the domain", "[5, 3.5, 3.5]"});
    s.refine[0].region = {core::Vec3(2, 2, 2), core::Vec3(1, 3, 3)}; // min > max on x
    expectRejected(s, {"domain.refine[0].region", "min <= max"});
    s.refine[0].region = {core::Vec3(-0.5, 1, 1), core::Vec3(1, 2, 2)};
    expectRejected(s, {"domain.refine[0].region", "[-0.5, 1, 1]"});
}

TEST(SpecValidation, RejectsMixedCellsPerBlock) {
    ForestSpec s = good();
    s.cellsPerBlock = {16, 16, 0};
    expectRejected(s, {"domain.cells_per_block", "[16, 16, 0]"});
    s.cellsPerBlock = {-1, -1, -1};
    expectRejected(s, {"domain.cells_per_block"});
}

TEST(SpecValidation, ForestRejectsBadWeights) {
    core::Comm world;
    EXPECT_THROW(BlockForest(world, good(), [](core::AABB const&, int) { return -1.0; }),
                 core::InputError);
    EXPECT_THROW(BlockForest(world, good(),
                             [](core::AABB const& b, int) {
                                 return b.min[0] > 2 ? std::numeric_limits<double>::quiet_NaN()
                                                     : 1.0;
                             }),
                 core::InputError);
}
