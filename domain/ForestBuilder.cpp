#include "domain/ForestBuilder.hpp"

#include "core/Error.hpp"
#include "core/memory/MemoryBudget.hpp"
#include "domain/HilbertCurve.hpp"
#include "domain/SfcPartition.hpp"
#include "domain/SpecValidation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace regolith::domain {

namespace {

int maxRefineLevel(ForestSpec const& spec) {
    validate(spec); // before anything reads the spec
    int level = 0;
    for (RefineRegion const& r : spec.refine)
        level = std::max(level, r.level);
    return level;
}

LatticeIndex floorDiv(LatticeIndex a, LatticeIndex b) {
    LatticeIndex q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0)))
        --q;
    return q;
}

/// Box of child k of a node with box `parent` (octant bit a set: upper half on axis a).
LatticeBox childBox(LatticeBox const& parent, int k) {
    LatticeIndex const half = (parent.hi[0] - parent.lo[0]) / 2;
    LatticeBox b;
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = parent.lo[a] + ((k >> a) & 1) * half;
        b.hi[a] = b.lo[a] + half;
    }
    return b;
}

} // namespace

void requireRefinementFits(ForestSpec const& spec, int ranks) {
    // Memory a block costs with the particle module's per-block state, measured: 8.8 KB a
    // block from 6,763 to 42,351 blocks (refinement levels 4 and 5, one rank), shared out
    // among the ranks. The blocks of the finest level in each region are a lower bound on
    // the leaves (2:1 balance adds more).
    constexpr double kBytesPerBlock = 8.0e3;
    int level = 0;
    double blocks = 0.0;
    for (RefineRegion const& r : spec.refine) {
        level = std::max(level, r.level);
        double n = 1.0;
        for (int a = 0; a < 3; ++a) {
            double const edge = spec.domain.extent()[a] /
                                spec.rootBlocks[static_cast<std::size_t>(a)] /
                                std::ldexp(1.0, r.level);
            n *= std::max(0.0, std::floor((std::min(r.region.max[a], spec.domain.max[a]) -
                                           std::max(r.region.min[a], spec.domain.min[a])) /
                                          edge) +
                                   1.0);
        }
        blocks += n;
    }
    core::requireMemory(
        blocks * kBytesPerBlock / ranks, "domain.refine",
        fmt::format("refining to level {} (at least {:.3g} blocks)", level, blocks));
}

ForestBuilder::ForestBuilder(ForestSpec const& spec)
    : m_geometry(spec.domain, spec.rootBlocks, spec.periodic, maxRefineLevel(spec)) {
    std::uint64_t const roots = m_geometry.rootCount();
    m_nodes.reserve(roots);
    for (std::uint64_t r = 0; r < roots; ++r)
        m_nodes.push_back(Node{BlockId::root(r)});
    for (RefineRegion const& region : spec.refine)
        refine(region);
    balance();
    orderLeaves();
}

// ---- refinement --------------------------------------------------------------------------

void ForestBuilder::refine(RefineRegion const& region) {
    if (region.level == 0)
        return;
    // Root blocks around the region (one extra on each side for closed contact), then the
    // exact closed test on the real boxes in refineNode.
    core::AABB const& d = m_geometry.domain();
    std::array<LatticeIndex, 3> lo{};
    std::array<LatticeIndex, 3> hi{};
    for (int a = 0; a < 3; ++a) {
        double const n = m_geometry.rootBlocks()[a];
        double const scale = n / (d.max[a] - d.min[a]);
        auto const first = std::floor((region.region.min[a] - d.min[a]) * scale) - 1.0;
        auto const last = std::floor((region.region.max[a] - d.min[a]) * scale) + 1.0;
        lo[a] = static_cast<LatticeIndex>(std::clamp(first, 0.0, n - 1.0));
        hi[a] = static_cast<LatticeIndex>(std::clamp(last, 0.0, n - 1.0));
    }
    for (LatticeIndex z = lo[2]; z <= hi[2]; ++z)
        for (LatticeIndex y = lo[1]; y <= hi[1]; ++y)
            for (LatticeIndex x = lo[0]; x <= hi[0]; ++x)
                refineNode(static_cast<std::int32_t>(m_geometry.rootIndex({x, y, z})),
                           region.region, region.level);
}

void ForestBuilder::refineNode(std::int32_t node, core::AABB const& region, int level) {
    BlockId const id = m_nodes[static_cast<std::size_t>(node)].id;
    if (id.level() >= level || !m_geometry.box(id).intersectsClosed(region))
        return;
    if (m_nodes[static_cast<std::size_t>(node)].firstChild < 0)
        split(node);
    std::int32_t const first = m_nodes[static_cast<std::size_t>(node)].firstChild;
    for (int k = 0; k < 8; ++k)
        refineNode(first + k, region, level);
}

void ForestBuilder::split(std::int32_t node) {
    if (m_nodes.size() + 8 > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
        throw core::InputError("domain.refine: the refinement would create more than 2^31 - 1 "
                               "blocks; use fewer or smaller refine regions");
    auto const first = static_cast<std::int32_t>(m_nodes.size());
    BlockId const id = m_nodes[static_cast<std::size_t>(node)].id;
    for (int k = 0; k < 8; ++k)
        m_nodes.push_back(Node{id.child(k)});
    m_nodes[static_cast<std::size_t>(node)].firstChild = first;
}

// ---- 2:1 balance -------------------------------------------------------------------------

bool ForestBuilder::wrapCell(LatticeCell& cell) const {
    for (int a = 0; a < 3; ++a) {
        LatticeIndex const n = m_geometry.latticeSize(a);
        if (cell[a] >= 0 && cell[a] < n)
            continue;
        if (!m_geometry.periodic()[a])
            return false;
        cell[a] -= floorDiv(cell[a], n) * n;
    }
    return true;
}

std::int32_t ForestBuilder::leafNodeAt(LatticeCell const& cell) const {
    LatticeIndex const s = m_geometry.rootSize();
    LatticeCell const root{cell[0] / s, cell[1] / s, cell[2] / s};
    auto node = static_cast<std::int32_t>(m_geometry.rootIndex(root));
    int bit = m_geometry.maxLevel() - 1;
    while (m_nodes[static_cast<std::size_t>(node)].firstChild >= 0) {
        int k = 0;
        for (int a = 0; a < 3; ++a)
            k |= static_cast<int>((cell[a] >> bit) & 1) << a;
        node = m_nodes[static_cast<std::size_t>(node)].firstChild + k;
        --bit;
    }
    return node;
}

void ForestBuilder::balance() {
    // Ripple propagation (as in p4est's balance, Sundar, Sampath & Biros, SIAM J. Sci. Comput.
    // 30(5), 2008): a leaf of level l looks at the 26 lattice cells just outside its faces,
    // edges and corners. The blocks of a forest are aligned dyadic boxes on one lattice (also
    // across periodic boundaries, the lattice period being a multiple of every block size),
    // so a touching block larger than the leaf contains one of these cells. Every coarser
    // leaf found with level < l - 1 is split until it is fine enough; new leaves are queued,
    // since they may in turn be too fine for their own coarse neighbours.
    std::vector<std::int32_t> work;
    for (std::size_t n = 0; n < m_nodes.size(); ++n)
        if (m_nodes[n].firstChild < 0)
            work.push_back(static_cast<std::int32_t>(n));
    while (!work.empty()) {
        std::int32_t const n = work.back();
        work.pop_back();
        Node const node = m_nodes[static_cast<std::size_t>(n)];
        int const level = node.id.level();
        if (node.firstChild >= 0 || level < 2)
            continue;
        LatticeBox const box = m_geometry.latticeBox(node.id);
        for (int d = 0; d < 27; ++d) {
            if (d == 13)
                continue; // the leaf itself
            int const dir[3] = {d % 3 - 1, (d / 3) % 3 - 1, d / 9 - 1};
            LatticeCell probe{};
            for (int a = 0; a < 3; ++a)
                probe[a] = dir[a] < 0 ? box.lo[a] - 1 : (dir[a] > 0 ? box.hi[a] : box.lo[a]);
            if (!wrapCell(probe))
                continue;
            for (;;) {
                std::int32_t const m = leafNodeAt(probe);
                if (m_nodes[static_cast<std::size_t>(m)].id.level() >= level - 1)
                    break;
                split(m);
                std::int32_t const first = m_nodes[static_cast<std::size_t>(m)].firstChild;
                for (int k = 0; k < 8; ++k)
                    work.push_back(first + k);
            }
        }
    }
}

// ---- curve order and assignment ----------------------------------------------------------

void ForestBuilder::orderLeaves() {
    int const bits = hilbertBitsFor(m_geometry.rootBlocks());
    std::uint64_t const roots = m_geometry.rootCount();
    std::vector<std::pair<std::uint64_t, std::uint64_t>> order; // (Hilbert index, root index)
    order.reserve(roots);
    for (std::uint64_t r = 0; r < roots; ++r) {
        LatticeCell const c = m_geometry.rootCoord(r);
        std::array<std::uint32_t, 3> const cell{static_cast<std::uint32_t>(c[0]),
                                                static_cast<std::uint32_t>(c[1]),
                                                static_cast<std::uint32_t>(c[2])};
        order.emplace_back(hilbertIndex(cell, bits), r);
    }
    std::sort(order.begin(), order.end());

    m_leaves.clear();
    std::vector<std::int32_t> stack;
    for (auto const& [h, root] : order) {
        stack.push_back(static_cast<std::int32_t>(root));
        while (!stack.empty()) {
            std::int32_t const n = stack.back();
            stack.pop_back();
            Node& node = m_nodes[static_cast<std::size_t>(n)];
            if (node.firstChild >= 0) {
                for (int k = 7; k >= 0; --k) // pushed in reverse: octant 0 comes out first
                    stack.push_back(node.firstChild + k);
                continue;
            }
            node.leaf = static_cast<std::int32_t>(m_leaves.size());
            m_leaves.push_back(ForestLeaf{node.id, m_geometry.latticeBox(node.id)});
        }
    }
}

void ForestBuilder::assign(BlockWeight const& weight, int ranks) {
    std::vector<double> w(m_leaves.size(), 1.0);
    if (weight)
        for (std::size_t i = 0; i < m_leaves.size(); ++i)
            w[i] = weight(m_geometry.box(m_leaves[i].box), m_leaves[i].id.level());
    std::vector<int> const owner = partitionCurve(w, ranks);
    for (std::size_t i = 0; i < m_leaves.size(); ++i) {
        m_leaves[i].owner = owner[i];
        m_leaves[i].weight = w[i];
    }
}

// ---- queries -----------------------------------------------------------------------------

std::size_t ForestBuilder::leafAt(LatticeCell const& cell) const {
    return static_cast<std::size_t>(m_nodes[static_cast<std::size_t>(leafNodeAt(cell))].leaf);
}

void ForestBuilder::neighbours(std::size_t leaf, std::vector<LeafLink>& out) const {
    out.clear();
    Search search{m_leaves[leaf].box, static_cast<std::uint32_t>(leaf), {0, 0, 0}};
    LatticeIndex const s = m_geometry.rootSize();
    // Root cells whose closed boxes can touch the leaf: one lattice cell around it.
    LatticeCell lo{};
    LatticeCell hi{};
    for (int a = 0; a < 3; ++a) {
        lo[a] = floorDiv(search.self.lo[a] - 1, s);
        hi[a] = floorDiv(search.self.hi[a], s);
    }
    for (LatticeIndex z = lo[2]; z <= hi[2]; ++z)
        for (LatticeIndex y = lo[1]; y <= hi[1]; ++y)
            for (LatticeIndex x = lo[0]; x <= hi[0]; ++x) {
                // Root cell (x, y, z) may lie outside the root grid: on a periodic axis it is
                // an image of a root; distinct cells give distinct (root, image) pairs.
                LatticeCell const cell{x, y, z};
                LatticeCell root = cell;
                bool inside = true;
                for (int a = 0; a < 3 && inside; ++a) {
                    LatticeIndex const n = m_geometry.rootBlocks()[a];
                    search.image[a] = 0;
                    if (root[a] >= 0 && root[a] < n)
                        continue;
                    inside = m_geometry.periodic()[a];
                    LatticeIndex const o = floorDiv(root[a], n);
                    root[a] -= o * n;
                    search.image[a] = static_cast<int>(o);
                }
                if (!inside)
                    continue;
                LatticeBox box; // the image's box: root cell in unwrapped lattice coordinates
                for (int a = 0; a < 3; ++a) {
                    box.lo[a] = cell[a] * s;
                    box.hi[a] = box.lo[a] + s;
                }
                collectTouching(static_cast<std::int32_t>(m_geometry.rootIndex(root)), box, search,
                                out);
            }
    std::sort(out.begin(), out.end(), [](LeafLink const& a, LeafLink const& b) {
        return a.leaf != b.leaf ? a.leaf < b.leaf : a.image < b.image;
    });
}

void ForestBuilder::collectTouching(std::int32_t n, LatticeBox const& box, Search const& search,
                                    std::vector<LeafLink>& out) const {
    if (!box.touches(search.self))
        return;
    Node const& node = m_nodes[static_cast<std::size_t>(n)];
    if (node.firstChild >= 0) {
        for (int k = 0; k < 8; ++k)
            collectTouching(node.firstChild + k, childBox(box, k), search, out);
        return;
    }
    auto const l = static_cast<std::uint32_t>(node.leaf);
    if (l == search.leaf && search.image == PeriodicImage{0, 0, 0})
        return;
    out.push_back(LeafLink{l, search.image});
}

} // namespace regolith::domain
