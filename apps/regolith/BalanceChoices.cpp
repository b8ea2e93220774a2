#include "apps/regolith/BalanceChoices.hpp"

#include "apps/regolith/BlockPlacement.hpp"
#include "apps/regolith/DynamicBalance.hpp"
#include "core/Error.hpp"
#include "coupling/gravity/GravityMethod.hpp"

#include <fmt/format.h>

#include <array>
#include <limits>
#include <string>

namespace regolith::apps {

namespace {

/// balance.every: "auto" resolved; an explicit interval checked against what can move.
void resolveEvery(core::Comm const& comm, SceneDescription& scene, std::vector<AutoChoice>& out) {
    BalanceSection& balance = scene.balance;
    bool const fixed = scene.forest.balance == domain::ForestSpec::Balance::Blocks;
    if (balance.everyAuto) {
        balance.everyAuto = false;
        balance.every = comm.size() > 1 && !fixed ? autoBalanceEvery(scene.time.steps) : 0;
        balance.adapts = balance.every > 0;
        out.push_back({"balance.every", fmt::format("{}", balance.every),
                       comm.size() == 1 ? "one rank: nothing to balance"
                       : fixed          ? "domain.balance = \"blocks\" weighs every block the same"
                                        : "the ranks' loads measured every twentieth of the "
                                          "run's steps, within 10 to 100, more often while the "
                                          "blocks move; the blocks re-cut when they differ by "
                                          "more than balance.threshold"});
        return;
    }
    if (balance.every == 0)
        return;
    if (fixed)
        throw core::InputError(fmt::format("balance.every = {}: domain.balance = \"blocks\" "
                                           "weighs every block the same, so the blocks never "
                                           "move; expected 0, or domain.balance = \"load\"",
                                           balance.every));
    if (comm.size() == 1)
        throw core::InputError(fmt::format("balance.every = {}: the run has one rank, whose "
                                           "blocks cannot move; expected 0 (or \"auto\") on one "
                                           "rank",
                                           balance.every));
}

/// Why the blocks of `scene` cannot split on `ranks` ranks, or nullptr. Pre: balance.every
/// resolved.
char const* whyNoSplit(SceneDescription const& scene, int ranks) {
    if (ranks == 1)
        return "the run has one rank, whose blocks are not re-cut";
    if (scene.balance.every == 0)
        return "the blocks are not re-cut during the run (balance.every = 0)";
    coupling::GravityMethodEntry const* gravity = coupling::findGravityMethod(scene.gravity.self);
    if (gravity && gravity->usesGrid)
        return "the grid gravity's cells are the blocks' (a split would change its resolution)";
    if (scene.sync.method == particles::SyncMethod::NextNeighbour)
        return "sync.method = \"nns\" needs every grain below the edges of its blocks";
    return nullptr;
}

/// balance.split_levels: "auto" resolved; explicit levels checked against what can split.
void resolveSplit(core::Comm const& comm, SceneDescription& scene, std::vector<AutoChoice>& out) {
    BalanceSection& balance = scene.balance;
    char const* const why = whyNoSplit(scene, comm.size());
    if (balance.splitAuto) {
        balance.splitAuto = false;
        balance.splitLevels = why ? 0 : kAutoSplitLevels;
        out.push_back(
            {"balance.split_levels", fmt::format("{}", balance.splitLevels),
             why ? std::string(why)
                 : fmt::format("where no cut of whole blocks evens the loads (a block "
                               "outweighs a rank's share, or the split's cut costs less with "
                               "its shadows), the blocks above {:.3g} of a rank's share split, "
                               "down to {} levels below the scene's blocks",
                               splitShare(balance.threshold), kAutoSplitLevels)});
        return;
    }
    if (balance.splitLevels > 0 && why)
        throw core::InputError(
            fmt::format("balance.split_levels = {}: the blocks cannot split: {}; expected 0",
                        balance.splitLevels, why));
}

/// The factorisation n of `ranks` whose blocks (extent / n per axis) have the least surface;
/// ties go to the first found, the larger count along the lower axis.
std::array<int, 3> leastSurfaceGrid(core::Vec3 const& extent, int ranks) {
    std::array<int, 3> best{ranks, 1, 1};
    double bestSurface = std::numeric_limits<double>::infinity();
    for (int nx = ranks; nx >= 1; --nx) {
        if (ranks % nx != 0)
            continue;
        for (int ny = ranks / nx; ny >= 1; --ny) {
            if (ranks / nx % ny != 0)
                continue;
            int const nz = ranks / nx / ny;
            double const bx = extent.x() / nx, by = extent.y() / ny, bz = extent.z() / nz;
            double const surface = bx * by + by * bz + bz * bx;
            if (surface < bestSurface * (1.0 - 1e-12)) {
                bestSurface = surface;
                best = {nx, ny, nz};
            }
        }
    }
    return best;
}

} // namespace

AutoChoice resolveRootBlocks(core::Comm const& comm, SceneDescription& scene) {
    domain::ForestSpec& forest = scene.forest;
    auto const value = [&forest] {
        auto const& n = forest.rootBlocks;
        return fmt::format("[{}, {}, {}]", n[0], n[1], n[2]);
    };
    if (!forest.rootBlocksAuto)
        return {};
    forest.rootBlocksAuto = false;
    coupling::GravityMethodEntry const* gravity = coupling::findGravityMethod(scene.gravity.self);
    bool const cells = forest.cellsPerBlock[0] > 0 || (gravity && gravity->usesGrid);
    char const* why = comm.size() == 1         ? "one rank"
                      : cells                  ? "the grid's cells are counted per block: set "
                                                 "domain.blocks to cut the grid for the ranks"
                      : !forest.refine.empty() ? "[[domain.refine]] levels count from the root "
                                                 "blocks: set domain.blocks for the ranks"
                                               : nullptr;
    if (why)
        return {"domain.blocks", value(), why};
    forest.rootBlocks = leastSurfaceGrid(forest.domain.extent(), comm.size());
    return {"domain.blocks", value(),
            "one block per rank, the rank grid whose blocks have the least surface; more blocks "
            "split where the loads need them (balance.split_levels)"};
}

std::vector<AutoChoice> resolveBalanceChoices(core::Comm const& comm, SceneDescription& scene) {
    std::vector<AutoChoice> out;
    resolveEvery(comm, scene, out);
    resolveSplit(comm, scene, out);
    return out;
}

} // namespace regolith::apps
