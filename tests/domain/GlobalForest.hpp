#pragma once
/// Test helpers: every rank's blocks and links gathered on every rank, brute-force references
/// over all blocks and all periodic images, and the forests the tests run on.
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestSpec.hpp"

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace regolith::domain::test {

/// A neighbour link as (id, image): what identifies it.
struct LinkKey {
    std::uint64_t id = 0;
    PeriodicImage image{0, 0, 0};
    friend auto operator<=>(LinkKey const&, LinkKey const&) = default;
};
std::ostream& operator<<(std::ostream& os, LinkKey const& k);

struct GlobalBlock {
    Block block;
    int heldBy = -1; ///< rank whose blocks() listed it
};

/// All blocks of all ranks, sorted by curveIndex, on every rank. Collective over `comm`.
std::vector<GlobalBlock> gatherBlocks(core::Comm const& comm, BlockForest const& forest);

/// All periodic images to try: {-1, 0, 1} on periodic axes, {0} on the others.
std::vector<PeriodicImage> candidateImages(std::array<bool, 3> const& periodic);

/// Real translation of image o: o * extent (image o of a box is box.shifted(translation(o))).
core::Vec3 translation(core::AABB const& domain, PeriodicImage const& o);

/// Closed contact with a tolerance `tol` per axis (for shifted boxes, whose faces may differ
/// from the touching face by rounding; true gaps are at least one finest block edge).
bool touchesWithin(core::AABB const& a, core::AABB const& b, core::Vec3 const& tol);

/// Smallest block edge per axis over all blocks.
core::Vec3 finestEdge(std::vector<GlobalBlock> const& all);

/// Brute force: every (block, image) whose closed image touches `a` (tolerance 1e-6 of the
/// finest edge), except `a` itself with image 0. Sorted.
std::vector<LinkKey> touchingImages(std::vector<GlobalBlock> const& all, Block const& a,
                                    core::AABB const& domain, std::array<bool, 3> const& periodic);

std::vector<LinkKey> keysOf(std::vector<BlockLink const*> const& links);

/// A named forest specification used by several tests.
struct ForestCase {
    std::string name;
    ForestSpec spec;
    Subdomains subdomains = Subdomains::Blocks; ///< what the forest's blocks() are
};
/// gtest prints a case by its name.
inline void PrintTo(ForestCase const& c, std::ostream* os) {
    *os << c.name;
}
/// Unrefined, periodic, refined (incl. across periodic boundaries), one and two blocks per
/// periodic axis, extreme aspect ratios. Each has at most a few hundred blocks.
std::vector<ForestCase> forestCases();
/// forestCases() twice: as blocks, and with each rank's blocks merged (Subdomains::RankBoxes,
/// names ending in "Merged").
std::vector<ForestCase> forestCasesBothWays();

/// Deterministic pseudo-random weight in [0.1, 10) from the block's box and level.
double randomWeight(core::AABB const& box, int level);

} // namespace regolith::domain::test
