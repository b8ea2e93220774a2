#pragma once
/// The octree of Barnes & Hut (1986, Nature 324, 446) over point masses, with the moments
/// every tree method here needs: mass, centre of mass, traceless quadrupole about the centre
/// of mass, b_max (Salmon & Warren 1994, J. Comput. Phys. 111, 136) and the opening radius.
#include "gravity/common/PointMasses.hpp"
#include "gravity/tree/TreeOptions.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace regolith::gravity::tree {

/// One cubic cell. Trivially copyable, so that locally essential trees travel as raw bytes.
struct TreeNode {
    double centre[3] = {0, 0, 0}; ///< geometric centre of the cube, m
    double half = 0.0;            ///< half the edge, m
    double com[3] = {0, 0, 0};    ///< centre of mass, m
    double mass = 0.0;            ///< kg
    /// Traceless quadrupole Q_ab = Σ m (3 d_a d_b - d² δ_ab), d = x - com, in kg m²; order
    /// xx, yy, zz, xy, xz, yz.
    double quad[6] = {0, 0, 0, 0, 0, 0};
    double bmax = 0.0; ///< largest distance from com to a grain centre of the cell, m
    /// The cell acts as a multipole on points farther than rcrit from its com; rcrit from
    /// the OpeningCriterion (TreeOptions.hpp). Each form guards against the "detonating
    /// galaxy" failure of the plain l/d < θ test (Salmon & Warren 1994: a com near a corner
    /// lets a target inside the cell pass), through b_max (measured from the com) or δ.
    double rcrit = 0.0;
    std::int32_t firstChild = -1; ///< children are contiguous: [firstChild, +childCount)
    std::int32_t childCount = 0;
    std::int32_t begin = 0; ///< grains [begin, end) in tree order (leaves)
    std::int32_t end = 0;
    /// 1 in a locally essential tree for a cell its sender found acceptable for every box of
    /// the receiver: no children, no grains, always used as a multipole.
    std::int32_t closed = 0;
    std::int32_t level = 0; ///< depth below the root

    [[nodiscard]] bool isLeaf() const { return childCount == 0 && closed == 0; }
    [[nodiscard]] std::int32_t count() const { return end - begin; }
};

/// A read-only view of a tree: nodes (root first, children after their parent) and its
/// grains in tree order.
struct TreeView {
    std::span<TreeNode const> nodes;
    std::span<double const> x, y, z, m;
};

struct OctreeBuildOptions {
    int leafSize = 8;       ///< split cells holding more grains than this ...
    double minEdge = 0.0;   ///< ... unless their edge is at most this (m; tree-at-nodes)
    double theta = 0.5;     ///< for rcrit
    bool quadrupole = true; ///< compute quadrupoles (zero otherwise)
    OpeningCriterion criterion = OpeningCriterion::BmaxPlusOffset; ///< for rcrit
};

/// An octree over a set of grains, owning copies of their data in tree order.
class Octree {
public:
    /// Builds the tree over `grains` (validated by the caller). The root is the bounding
    /// cube of the grains; empty cells are not stored; cells deeper than 48 levels stay
    /// leaves (coincident grains). O(N log N). Not collective.
    static Octree build(PointMasses const& grains, OctreeBuildOptions const& options);

    [[nodiscard]] TreeView view() const { return {m_nodes, m_x, m_y, m_z, m_m}; }
    [[nodiscard]] std::vector<TreeNode> const& nodes() const { return m_nodes; }
    /// Original index of the grain at tree position k.
    [[nodiscard]] std::vector<std::int32_t> const& order() const { return m_order; }
    [[nodiscard]] std::span<double const> x() const { return m_x; }
    [[nodiscard]] std::span<double const> y() const { return m_y; }
    [[nodiscard]] std::span<double const> z() const { return m_z; }
    [[nodiscard]] std::span<double const> m() const { return m_m; }
    /// Radii in tree order (empty if the grains had none).
    [[nodiscard]] std::span<double const> r() const { return m_r; }
    [[nodiscard]] bool empty() const { return m_nodes.empty(); }

private:
    void split(std::int32_t node, int depth, OctreeBuildOptions const& options,
               std::vector<std::int32_t>& scratch, PointMasses const& grains);
    void computeMoments(OctreeBuildOptions const& options);

    std::vector<TreeNode> m_nodes;
    std::vector<std::int32_t> m_order;
    std::vector<double> m_x, m_y, m_z, m_m, m_r;
};

} // namespace regolith::gravity::tree
