// gravity.self = "tree" and "mutual-tree": Barnes–Hut with locally essential trees, and the
// momentum-conserving dual-tree walk over the grains gathered on every rank (gravity/tree).
#include "coupling/gravity/GravityMethod.hpp"
#include "gravity/tree/BarnesHut.hpp"
#include "gravity/tree/MutualTree.hpp"
#include "gravity/tree/TreeOptions.hpp"

#include <vector>

namespace regolith::coupling {

namespace {

gravity::tree::TreeOptions treeOptions(SelfGravityConfig const& c) {
    gravity::tree::TreeOptions tree;
    tree.G = c.G;
    tree.softening = c.softening;
    tree.theta = c.theta;
    tree.allowLargeTheta = c.allowLargeTheta;
    return tree;
}

class BarnesHutMethod final : public GravityMethod {
public:
    explicit BarnesHutMethod(GravityMethodInput const& in)
        : m_tree(in.comm, treeOptions(in.config)) {
        for (domain::Block const& b : in.forest.blocks())
            m_boxes.push_back(b.aabb);
    }
    double evaluate(gravity::PointMasses const& grains, gravity::FieldOut out) override {
        return m_tree.evaluate(grains, out, m_boxes);
    }

private:
    gravity::tree::BarnesHut m_tree;
    std::vector<core::AABB> m_boxes; ///< this rank's blocks (sharpen the tree's pruning)
};

class MutualTreeMethod final : public GravityMethod {
public:
    explicit MutualTreeMethod(GravityMethodInput const& in)
        : m_comm(in.comm)
        , m_tree(treeOptions(in.config)) {}
    double evaluate(gravity::PointMasses const& grains, gravity::FieldOut out) override {
        return m_tree.evaluateGathered(m_comm, grains, out);
    }

private:
    core::Comm const& m_comm;
    gravity::tree::MutualTree m_tree;
};

} // namespace

GravityMethodEntry barnesHutMethod() {
    GravityMethodEntry e;
    e.name = "tree";
    e.softens = true;
    e.usesTheta = true;
    e.make = makeGravityMethod<BarnesHutMethod>;
    return e;
}

GravityMethodEntry mutualTreeMethod() {
    GravityMethodEntry e;
    e.name = "mutual-tree";
    e.softens = true;
    e.usesTheta = true;
    e.make = makeGravityMethod<MutualTreeMethod>;
    return e;
}

} // namespace regolith::coupling
