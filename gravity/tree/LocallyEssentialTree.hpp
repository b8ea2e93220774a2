#pragma once
/// Locally essential trees (Salmon 1991, PhD thesis, Caltech; Warren & Salmon 1993,
/// "A parallel hashed oct-tree N-body algorithm", SC'93): the part of a rank's tree that
/// another rank needs to evaluate the field at any point of its boxes. A cell acceptable
/// for every box of the receiver is sent closed (its multipole only); a cell that is not is
/// opened, and an opened leaf sends its grains. Far receivers get a handful of cells, so the
/// traffic grows with the surface between ranks, not with N.
#include "core/math/AABB.hpp"
#include "core/mpi/Buffer.hpp"
#include "gravity/tree/Octree.hpp"

#include <span>
#include <vector>

namespace regolith::gravity::tree {

/// A pruned copy of a tree; the same shape as an Octree (root first, contiguous children).
struct LocallyEssentialTree {
    std::vector<TreeNode> nodes;
    std::vector<double> x, y, z, m;

    [[nodiscard]] TreeView view() const { return {nodes, x, y, z, m}; }
};

/// The part of `tree` that targets inside `boxes` need, by the same acceptance test as the
/// walk (com farther than rcrit from the closed box). Empty if `tree` or `boxes` is empty.
/// Not collective.
[[nodiscard]] LocallyEssentialTree pruneFor(TreeView const& tree,
                                            std::span<core::AABB const> boxes);

void pack(core::SendBuffer& out, LocallyEssentialTree const& let);
/// Throws core::BufferError on a short or corrupt buffer, core::Error if the tree's links
/// point outside it.
[[nodiscard]] LocallyEssentialTree unpackLocallyEssentialTree(core::RecvBuffer& in);

} // namespace regolith::gravity::tree
