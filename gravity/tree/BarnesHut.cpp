#include "gravity/tree/BarnesHut.hpp"

#include "gravity/tree/InteractionList.hpp"
#include "gravity/tree/LocallyEssentialTree.hpp"
#include "gravity/tree/Octree.hpp"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <limits>

namespace regolith::gravity::tree {

namespace {

core::AABB emptyBox() {
    double const inf = std::numeric_limits<double>::infinity();
    return {core::Vec3::Constant(inf), core::Vec3::Constant(-inf)};
}

void grow(core::AABB& box, core::Vec3 const& p) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
}

bool isEmpty(core::AABB const& box) {
    return (box.min.array() > box.max.array()).any();
}

/// The groups of targets: the highest cells holding at most `groupSize` grains.
std::vector<std::int32_t> targetGroups(Octree const& tree, int groupSize) {
    std::vector<std::int32_t> groups;
    std::vector<std::int32_t> stack{0};
    auto const& nodes = tree.nodes();
    while (!stack.empty()) {
        std::int32_t const k = stack.back();
        stack.pop_back();
        TreeNode const& c = nodes[static_cast<std::size_t>(k)];
        if (c.count() <= groupSize || c.childCount == 0) {
            groups.push_back(k);
        } else {
            for (std::int32_t j = 0; j < c.childCount; ++j)
                stack.push_back(c.firstChild + j);
        }
    }
    return groups;
}

} // namespace

std::vector<core::AABB> tightBoxes(PointMasses const& grains,
                                   std::span<core::AABB const> blockBoxes) {
    std::vector<core::AABB> boxes(blockBoxes.size() + 1, emptyBox());
    for (std::size_t i = 0; i < grains.size(); ++i) {
        core::Vec3 const p(grains.x[i], grains.y[i], grains.z[i]);
        std::size_t k = 0;
        while (k < blockBoxes.size() && !blockBoxes[k].contains(p))
            ++k;
        grow(boxes[k], p);
    }
    std::erase_if(boxes, isEmpty);
    return boxes;
}

BarnesHut::BarnesHut(core::Comm const& comm, TreeOptions const& options)
    : m_comm(comm.duplicate())
    , m_options(options)
    , m_exchange(m_comm) {
    validate(m_options);
}

std::vector<std::vector<core::AABB>>
BarnesHut::gatherBoxes(PointMasses const& local, std::span<core::AABB const> blockBoxes) {
    std::vector<core::AABB> const mine = tightBoxes(local, blockBoxes);
    std::vector<double> flat;
    for (core::AABB const& b : mine)
        flat.insert(flat.end(), {b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z()});
    std::vector<int> counts;
    std::vector<double> const all = m_comm.allGatherVarying<double>(flat, &counts);
    std::vector<std::vector<core::AABB>> boxes(counts.size());
    int begin = 0; // rank r's boxes: [begin, begin + counts[r]) of `all`, 6 values each
    for (std::size_t r = 0; r < counts.size(); begin += counts[r], ++r)
        for (int k = begin; k < begin + counts[r]; k += 6) {
            double const* b = all.data() + k;
            boxes[r].push_back({core::Vec3(b[0], b[1], b[2]), core::Vec3(b[3], b[4], b[5])});
        }
    return boxes;
}

double BarnesHut::evaluate(PointMasses const& local, FieldOut out,
                           std::span<core::AABB const> blockBoxes) {
    validatePointMassesCollective(m_comm, local, "gravity");
    validateFieldOut(out, local.size());
    m_stats = {};
    Octree const tree = Octree::build(local, {m_options.leafSize, 0.0, m_options.theta,
                                              m_options.quadrupole, m_options.criterion});

    // Locally essential trees: each rank sends every other rank the part it needs.
    auto const boxes = gatherBoxes(local, blockBoxes);
    for (int r = 0; r < m_comm.size(); ++r) {
        auto const& theirs = boxes[static_cast<std::size_t>(r)];
        if (r == m_comm.rank() || theirs.empty() || tree.empty())
            continue;
        LocallyEssentialTree const let = pruneFor(tree.view(), theirs);
        core::SendBuffer& buf = m_exchange.sendBuffer(r);
        pack(buf, let);
        m_stats.nodesSent += static_cast<long long>(let.nodes.size());
        m_stats.grainsSent += static_cast<long long>(let.x.size());
        m_stats.bytesSent += static_cast<long long>(buf.size());
    }
    m_exchange.start();
    std::vector<LocallyEssentialTree> imported;
    m_exchange.wait(
        [&](int, core::RecvBuffer& in) { imported.push_back(unpackLocallyEssentialTree(in)); });

    // Grouped walks over the own tree and every imported one.
    double const eps2 = m_options.softening * m_options.softening;
    InteractionList list;
    std::vector<std::int32_t> stack;
    std::vector<double> scratch(4 * 4096);
    double energy = 0.0;
    if (!tree.empty()) {
        for (std::int32_t const g : targetGroups(tree, m_options.groupSize)) {
            TreeNode const& group = tree.nodes()[static_cast<std::size_t>(g)];
            auto const b = static_cast<std::size_t>(group.begin);
            std::size_t const n = static_cast<std::size_t>(group.count());
            core::AABB box = emptyBox();
            for (std::size_t i = b; i < b + n; ++i)
                grow(box, core::Vec3(tree.x()[i], tree.y()[i], tree.z()[i]));
            list.clear();
            collectInteractions(tree.view(), box, m_options.quadrupole, list, stack);
            for (auto const& let : imported)
                collectInteractions(let.view(), box, m_options.quadrupole, list, stack);
            m_stats.cellInteractions += static_cast<long long>(list.cellCount() * n);
            m_stats.grainInteractions += static_cast<long long>(list.grainCount() * n);
            // Targets in chunks that fit the scratch (a leaf at the depth limit may be big).
            for (std::size_t c0 = 0; c0 < n; c0 += 4096) {
                std::size_t const len = std::min<std::size_t>(4096, n - c0);
                double* ax = scratch.data();
                double* ay = ax + 4096;
                double* az = ay + 4096;
                double* phi = az + 4096;
                std::fill(ax, ax + len, 0.0);
                std::fill(ay, ay + len, 0.0);
                std::fill(az, az + len, 0.0);
                std::fill(phi, phi + len, 0.0);
                std::size_t const t0 = b + c0;
                list.evaluate(tree.x().data() + t0, tree.y().data() + t0, tree.z().data() + t0, len,
                              m_options.G, eps2, ax, ay, az, phi);
                for (std::size_t i = 0; i < len; ++i) {
                    auto const orig = static_cast<std::size_t>(tree.order()[t0 + i]);
                    out.ax[orig] = ax[i];
                    out.ay[orig] = ay[i];
                    out.az[orig] = az[i];
                    if (!out.phi.empty())
                        out.phi[orig] = phi[i];
                    energy += 0.5 * local.m[orig] * phi[i];
                }
            }
        }
    }
    return m_comm.allReduce(energy, core::ReduceOp::Sum);
}

} // namespace regolith::gravity::tree
