#include "gravity/tree/LocallyEssentialTree.hpp"

#include "core/Error.hpp"

namespace regolith::gravity::tree {

namespace {

class Pruner {
public:
    Pruner(TreeView const& tree, std::span<core::AABB const> boxes, LocallyEssentialTree& out)
        : m_tree(tree)
        , m_boxes(boxes)
        , m_out(out) {}

    /// Copies source node `src` into out.nodes[dst], recursing into what must be opened.
    void emit(std::int32_t src, std::size_t dst) {
        TreeNode node = m_tree.nodes[static_cast<std::size_t>(src)];
        if (node.closed != 0 || acceptableForAllBoxes(node)) {
            node.closed = 1;
            node.childCount = 0;
            node.firstChild = -1;
            node.begin = node.end = 0;
        } else if (node.childCount == 0) {
            auto const b = static_cast<long>(node.begin);
            auto const e = static_cast<long>(node.end);
            node.begin = static_cast<std::int32_t>(m_out.x.size());
            m_out.x.insert(m_out.x.end(), m_tree.x.begin() + b, m_tree.x.begin() + e);
            m_out.y.insert(m_out.y.end(), m_tree.y.begin() + b, m_tree.y.begin() + e);
            m_out.z.insert(m_out.z.end(), m_tree.z.begin() + b, m_tree.z.begin() + e);
            m_out.m.insert(m_out.m.end(), m_tree.m.begin() + b, m_tree.m.begin() + e);
            node.end = static_cast<std::int32_t>(m_out.x.size());
        } else {
            std::size_t const first = m_out.nodes.size();
            m_out.nodes.resize(first + static_cast<std::size_t>(node.childCount));
            for (std::int32_t k = 0; k < node.childCount; ++k)
                emit(node.firstChild + k, first + static_cast<std::size_t>(k));
            node.firstChild = static_cast<std::int32_t>(first);
            node.begin = node.end = 0; // its grains, if any were needed, are in its leaves
        }
        m_out.nodes[dst] = node;
    }

private:
    [[nodiscard]] bool acceptableForAllBoxes(TreeNode const& c) const {
        core::Vec3 const com(c.com[0], c.com[1], c.com[2]);
        for (core::AABB const& box : m_boxes)
            if (!(box.sqDistance(com) > c.rcrit * c.rcrit))
                return false;
        return true;
    }

    TreeView m_tree;
    std::span<core::AABB const> m_boxes;
    LocallyEssentialTree& m_out;
};

} // namespace

LocallyEssentialTree pruneFor(TreeView const& tree, std::span<core::AABB const> boxes) {
    LocallyEssentialTree out;
    if (tree.nodes.empty() || boxes.empty())
        return out;
    out.nodes.resize(1);
    Pruner(tree, boxes, out).emit(0, 0);
    return out;
}

void pack(core::SendBuffer& out, LocallyEssentialTree const& let) {
    out << let.nodes << let.x << let.y << let.z << let.m;
}

LocallyEssentialTree unpackLocallyEssentialTree(core::RecvBuffer& in) {
    LocallyEssentialTree let;
    in >> let.nodes >> let.x >> let.y >> let.z >> let.m;
    auto const nNodes = static_cast<std::int64_t>(let.nodes.size());
    auto const nGrains = static_cast<std::int64_t>(let.x.size());
    if (let.y.size() != let.x.size() || let.z.size() != let.x.size() ||
        let.m.size() != let.x.size())
        throw core::Error("gravity tree: locally essential tree with unequal grain arrays");
    for (TreeNode const& c : let.nodes) {
        bool const childrenOk =
            c.childCount == 0 || (c.firstChild > 0 && c.firstChild + c.childCount <= nNodes);
        bool const grainsOk = c.begin >= 0 && c.begin <= c.end && c.end <= nGrains;
        if (!childrenOk || !grainsOk)
            throw core::Error("gravity tree: corrupt locally essential tree received");
    }
    return let;
}

} // namespace regolith::gravity::tree
