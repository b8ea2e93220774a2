#include "domain/RankBoxes.hpp"

#include <algorithm>
#include <tuple>

namespace regolith::domain {

SubdomainCut oneBoxPerLeaf(std::vector<ForestLeaf> const& leaves) {
    SubdomainCut cut;
    cut.boxes.reserve(leaves.size());
    cut.leaves.reserve(leaves.size());
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        auto const l = static_cast<std::uint32_t>(i);
        cut.boxes.push_back(RankBox{leaves[i].box, leaves[i].owner, l, l + 1});
        cut.leaves.push_back(l);
    }
    return cut;
}

namespace {

/// A box while one rank's leaves are merged.
struct Piece {
    LatticeBox lattice;
    std::vector<std::uint32_t> leaves;
};

/// One sweep along `axis` over one rank's pieces: sorted by their extent across the axis,
/// then along it, so that pieces that can join are neighbours in the order. Returns whether
/// any joined.
bool joinAlong(int axis, std::vector<Piece>& pieces) {
    int const b = (axis + 1) % 3;
    int const c = (axis + 2) % 3;
    auto const across = [b, c](LatticeBox const& x) {
        return std::tuple(x.lo[b], x.hi[b], x.lo[c], x.hi[c]);
    };
    std::sort(pieces.begin(), pieces.end(), [&](Piece const& x, Piece const& y) {
        return std::tuple(across(x.lattice), x.lattice.lo[axis]) <
               std::tuple(across(y.lattice), y.lattice.lo[axis]);
    });
    std::vector<Piece> joined;
    joined.reserve(pieces.size());
    for (Piece& piece : pieces) {
        if (!joined.empty()) {
            Piece& last = joined.back();
            if (across(last.lattice) == across(piece.lattice) &&
                last.lattice.hi[axis] == piece.lattice.lo[axis]) {
                last.lattice.hi[axis] = piece.lattice.hi[axis];
                last.leaves.insert(last.leaves.end(), piece.leaves.begin(), piece.leaves.end());
                continue;
            }
        }
        joined.push_back(std::move(piece));
    }
    bool const any = joined.size() < pieces.size();
    pieces = std::move(joined);
    return any;
}

} // namespace

SubdomainCut mergeRankLeaves(std::vector<ForestLeaf> const& leaves) {
    SubdomainCut cut;
    cut.leaves.reserve(leaves.size());
    // A rank's leaves are one contiguous range of the curve (ForestBuilder::assign).
    for (std::size_t first = 0; first < leaves.size();) {
        int const owner = leaves[first].owner;
        std::size_t last = first;
        while (last < leaves.size() && leaves[last].owner == owner)
            ++last;
        std::vector<Piece> pieces;
        pieces.reserve(last - first);
        for (std::size_t i = first; i < last; ++i)
            pieces.push_back(Piece{leaves[i].box, {static_cast<std::uint32_t>(i)}});
        bool joined = true;
        while (joined) {
            joined = false;
            for (int axis = 0; axis < 3; ++axis)
                joined = joinAlong(axis, pieces) || joined;
        }
        for (Piece& piece : pieces)
            std::sort(piece.leaves.begin(), piece.leaves.end());
        std::sort(pieces.begin(), pieces.end(), [](Piece const& x, Piece const& y) {
            return x.leaves.front() < y.leaves.front();
        });
        for (Piece const& piece : pieces) {
            auto const begin = static_cast<std::uint32_t>(cut.leaves.size());
            cut.leaves.insert(cut.leaves.end(), piece.leaves.begin(), piece.leaves.end());
            cut.boxes.push_back(RankBox{piece.lattice, owner, begin,
                                        static_cast<std::uint32_t>(cut.leaves.size())});
        }
        first = last;
    }
    return cut;
}

} // namespace regolith::domain
