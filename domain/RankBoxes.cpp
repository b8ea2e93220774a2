#include "domain/RankBoxes.hpp"

#include <algorithm>
#include <tuple>

namespace regolith::domain {

std::vector<RankBox> oneBoxPerLeaf(std::vector<ForestLeaf> const& leaves) {
    std::vector<RankBox> boxes;
    boxes.reserve(leaves.size());
    for (std::size_t i = 0; i < leaves.size(); ++i)
        boxes.push_back(RankBox{leaves[i].box, leaves[i].owner, {static_cast<std::uint32_t>(i)}});
    return boxes;
}

namespace {

/// One sweep along `axis` over one rank's boxes: sorted by their extent across the axis, then
/// along it, so that boxes that can join are neighbours in the order. Returns whether any
/// joined.
bool joinAlong(int axis, std::vector<RankBox>& boxes) {
    int const b = (axis + 1) % 3;
    int const c = (axis + 2) % 3;
    auto const across = [b, c](LatticeBox const& x) {
        return std::tuple(x.lo[b], x.hi[b], x.lo[c], x.hi[c]);
    };
    std::sort(boxes.begin(), boxes.end(), [&](RankBox const& x, RankBox const& y) {
        return std::tuple(across(x.lattice), x.lattice.lo[axis]) <
               std::tuple(across(y.lattice), y.lattice.lo[axis]);
    });
    std::vector<RankBox> joined;
    joined.reserve(boxes.size());
    for (RankBox& box : boxes) {
        if (!joined.empty()) {
            RankBox& last = joined.back();
            if (across(last.lattice) == across(box.lattice) &&
                last.lattice.hi[axis] == box.lattice.lo[axis]) {
                last.lattice.hi[axis] = box.lattice.hi[axis];
                last.leaves.insert(last.leaves.end(), box.leaves.begin(), box.leaves.end());
                continue;
            }
        }
        joined.push_back(std::move(box));
    }
    bool const any = joined.size() < boxes.size();
    boxes = std::move(joined);
    return any;
}

} // namespace

std::vector<RankBox> mergeRankLeaves(std::vector<ForestLeaf> const& leaves) {
    std::vector<RankBox> merged;
    // A rank's leaves are one contiguous range of the curve (ForestBuilder::assign).
    for (std::size_t first = 0; first < leaves.size();) {
        std::size_t last = first;
        while (last < leaves.size() && leaves[last].owner == leaves[first].owner)
            ++last;
        std::vector<RankBox> boxes;
        for (std::size_t i = first; i < last; ++i)
            boxes.push_back(
                RankBox{leaves[i].box, leaves[i].owner, {static_cast<std::uint32_t>(i)}});
        bool joined = true;
        while (joined) {
            joined = false;
            for (int axis = 0; axis < 3; ++axis)
                joined = joinAlong(axis, boxes) || joined;
        }
        for (RankBox& box : boxes)
            std::sort(box.leaves.begin(), box.leaves.end());
        std::sort(boxes.begin(), boxes.end(), [](RankBox const& x, RankBox const& y) {
            return x.leaves.front() < y.leaves.front();
        });
        for (RankBox& box : boxes)
            merged.push_back(std::move(box));
        first = last;
    }
    return merged;
}

} // namespace regolith::domain
