#include "gravity/baselines/GridMethods.hpp"

#include "core/Error.hpp"
#include "core/mpi/AgreeOnInputError.hpp"
#include "gravity/common/GatherAll.hpp"
#include "gravity/tree/InteractionList.hpp"
#include "gravity/tree/Octree.hpp"
#include "gravity/tree/TreeOptions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace regolith::gravity::baselines {

namespace {

/// Node positions (SoA) and zeroed values for `keys`.
NodeField prepareNodes(NodeGrid const& grid, std::vector<std::uint64_t> keys,
                       std::vector<double>& px, std::vector<double>& py, std::vector<double>& pz) {
    NodeField f;
    f.keys = std::move(keys);
    std::size_t const n = f.keys.size();
    f.ax.assign(n, 0.0);
    f.ay.assign(n, 0.0);
    f.az.assign(n, 0.0);
    f.phi.assign(n, 0.0);
    px.resize(n);
    py.resize(n);
    pz.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        core::Vec3 const p = nodePosition(grid, f.keys[i]);
        px[i] = p.x();
        py[i] = p.y();
        pz[i] = p.z();
    }
    return f;
}

} // namespace

void validate(GridMethodOptions const& o) {
    validate(o.grid);
    tree::TreeOptions t;
    t.G = o.G;
    t.theta = o.theta;
    t.allowLargeTheta = o.allowLargeTheta;
    tree::validate(t);
    if (!(o.neighbourhood >= 0.0) || !std::isfinite(o.neighbourhood))
        throw core::InputError(fmt::format(
            "gravity.neighbourhood = {}: the neighbourhood radius must be finite and >= 0 m",
            o.neighbourhood));
}

namespace {

/// nodesAround, whose InputError (a grain beyond the grid's index range) only the ranks
/// holding such a grain would see: agreed on every rank, so none waits in the reduction at
/// the end of evaluate. (interpolateToGrains then looks up the same cells: it cannot fail.)
std::vector<std::uint64_t> agreedNodesAround(core::Comm const& comm,
                                             GridMethodOptions const& options,
                                             PointMasses const& local) {
    std::vector<std::uint64_t> keys;
    core::agreeOnInputError(comm,
                            [&] { keys = nodesAround(options.grid, local, options.expand64); });
    return keys;
}

} // namespace

OccupiedCells::OccupiedCells(GridMethodOptions const& options)
    : m_options(options) {
    validate(m_options);
}

double OccupiedCells::evaluate(core::Comm const& comm, PointMasses const& local, FieldOut out) {
    validatePointMassesCollective(comm, local, "gravity");
    validateFieldOut(out, local.size());
    OwnedMasses const all = gatherAll(comm, local);
    PointMasses const sources = all.view();
    std::vector<double> px, py, pz;
    NodeField nodes =
        prepareNodes(m_options.grid, agreedNodesAround(comm, m_options, local), px, py, pz);
    std::size_t const n = nodes.keys.size();
    constexpr std::size_t kTile = 256;
    for (std::size_t t0 = 0; t0 < n; t0 += kTile) {
        std::size_t const len = std::min(kTile, n - t0);
        accumulateSphereField(px.data() + t0, py.data() + t0, pz.data() + t0, len, sources, 0,
                              sources.size(), m_options.G, nodes.ax.data() + t0,
                              nodes.ay.data() + t0, nodes.az.data() + t0, nodes.phi.data() + t0);
    }
    m_stats.nodes = static_cast<long long>(n);
    m_stats.interactions = static_cast<long long>(n * sources.size());
    double const energy = interpolateToGrains(m_options.grid, nodes, local, m_options.G, out);
    return comm.allReduce(energy, core::ReduceOp::Sum);
}

TreeAtNodes::TreeAtNodes(GridMethodOptions const& options)
    : m_options(options) {
    validate(m_options);
}

double TreeAtNodes::evaluate(core::Comm const& comm, PointMasses const& local, FieldOut out) {
    validatePointMassesCollective(comm, local, "gravity");
    validateFieldOut(out, local.size());
    OwnedMasses const all = gatherAll(comm, local);
    // Subdivision stops at the grid's box size (or at one grain).
    tree::Octree const octree = tree::Octree::build(
        all.view(), {1, m_options.grid.spacing, m_options.theta, m_options.quadrupole});
    PointMasses const grains{octree.x(), octree.y(), octree.z(), octree.m(), octree.r()};
    std::vector<double> px, py, pz;
    NodeField nodes =
        prepareNodes(m_options.grid, agreedNodesAround(comm, m_options, local), px, py, pz);
    tree::TreeView const view = octree.view();
    tree::InteractionList list;
    std::vector<std::int32_t> stack;
    double const nb2 = m_options.neighbourhood * m_options.neighbourhood;
    m_stats = {};
    m_stats.nodes = static_cast<long long>(nodes.keys.size());
    for (std::size_t i = 0; i < nodes.keys.size() && !view.nodes.empty(); ++i) {
        core::Vec3 const p(px[i], py[i], pz[i]);
        list.clear();
        stack.assign(1, 0);
        while (!stack.empty()) {
            tree::TreeNode const& c = view.nodes[static_cast<std::size_t>(stack.back())];
            stack.pop_back();
            core::Vec3 const com(c.com[0], c.com[1], c.com[2]);
            core::Vec3 const centre(c.centre[0], c.centre[1], c.centre[2]);
            core::Vec3 const gap =
                ((p - centre).cwiseAbs() - core::Vec3::Constant(c.half)).cwiseMax(0.0);
            bool const outsideNeighbourhood = gap.squaredNorm() > nb2;
            if (outsideNeighbourhood && (p - com).squaredNorm() > c.rcrit * c.rcrit) {
                list.addCell(c, m_options.quadrupole);
            } else if (c.childCount == 0) {
                accumulateSphereField(&px[i], &py[i], &pz[i], 1, grains,
                                      static_cast<std::size_t>(c.begin),
                                      static_cast<std::size_t>(c.end), m_options.G, &nodes.ax[i],
                                      &nodes.ay[i], &nodes.az[i], &nodes.phi[i]);
                m_stats.interactions += c.count();
            } else {
                for (std::int32_t k = 0; k < c.childCount; ++k)
                    stack.push_back(c.firstChild + k);
            }
        }
        list.evaluate(&px[i], &py[i], &pz[i], 1, m_options.G, 0.0, &nodes.ax[i], &nodes.ay[i],
                      &nodes.az[i], &nodes.phi[i]);
        m_stats.interactions += static_cast<long long>(list.cellCount() + list.grainCount());
    }
    double const energy = interpolateToGrains(m_options.grid, nodes, local, m_options.G, out);
    return comm.allReduce(energy, core::ReduceOp::Sum);
}

} // namespace regolith::gravity::baselines
