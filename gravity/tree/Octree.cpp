#include "gravity/tree/Octree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace regolith::gravity::tree {

namespace {

constexpr int kMaxDepth = 48;

/// Adds the quadrupole of a point mass m at offset d (from the com) to q.
void addPointQuadrupole(double (&q)[6], double m, double dx, double dy, double dz) {
    double const d2 = dx * dx + dy * dy + dz * dz;
    q[0] += m * (3.0 * dx * dx - d2);
    q[1] += m * (3.0 * dy * dy - d2);
    q[2] += m * (3.0 * dz * dz - d2);
    q[3] += m * 3.0 * dx * dy;
    q[4] += m * 3.0 * dx * dz;
    q[5] += m * 3.0 * dy * dz;
}

} // namespace

Octree Octree::build(PointMasses const& grains, OctreeBuildOptions const& options) {
    Octree t;
    std::size_t const n = grains.size();
    if (n == 0)
        return t;
    double lo[3] = {grains.x[0], grains.y[0], grains.z[0]};
    double hi[3] = {lo[0], lo[1], lo[2]};
    for (std::size_t i = 0; i < n; ++i) {
        double const p[3] = {grains.x[i], grains.y[i], grains.z[i]};
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
        }
    }
    TreeNode root;
    double half = 0.0;
    for (int a = 0; a < 3; ++a) {
        root.centre[a] = 0.5 * (lo[a] + hi[a]);
        half = std::max(half, 0.5 * (hi[a] - lo[a]));
    }
    // Slightly larger than the bounding box, so every grain is strictly inside.
    root.half = half * (1.0 + 1e-9) + 1e-300;
    root.begin = 0;
    root.end = static_cast<std::int32_t>(n);
    t.m_nodes.reserve(2 * n / static_cast<std::size_t>(std::max(1, options.leafSize)) + 16);
    t.m_nodes.push_back(root);
    t.m_order.resize(n);
    std::iota(t.m_order.begin(), t.m_order.end(), 0);
    std::vector<std::int32_t> scratch(n);
    t.split(0, 0, options, scratch, grains);

    auto const gather = [&](std::span<double const> in, std::vector<double>& out) {
        out.resize(n);
        for (std::size_t k = 0; k < n; ++k)
            out[k] = in[static_cast<std::size_t>(t.m_order[k])];
    };
    gather(grains.x, t.m_x);
    gather(grains.y, t.m_y);
    gather(grains.z, t.m_z);
    gather(grains.m, t.m_m);
    if (!grains.r.empty())
        gather(grains.r, t.m_r);
    t.computeMoments(options);
    return t;
}

void Octree::split(std::int32_t node, int depth, OctreeBuildOptions const& options,
                   std::vector<std::int32_t>& scratch, PointMasses const& grains) {
    TreeNode const cell = m_nodes[static_cast<std::size_t>(node)];
    if (cell.count() <= options.leafSize || 2.0 * cell.half <= options.minEdge ||
        depth >= kMaxDepth)
        return;
    // Counting sort of the cell's grains by octant (bit 0: x, 1: y, 2: z above centre).
    std::array<std::int32_t, 8> counts{};
    auto const octant = [&](std::int32_t i) {
        auto const u = static_cast<std::size_t>(i);
        return (grains.x[u] >= cell.centre[0] ? 1 : 0) | (grains.y[u] >= cell.centre[1] ? 2 : 0) |
               (grains.z[u] >= cell.centre[2] ? 4 : 0);
    };
    for (std::int32_t k = cell.begin; k < cell.end; ++k)
        ++counts[static_cast<std::size_t>(octant(m_order[static_cast<std::size_t>(k)]))];
    std::array<std::int32_t, 8> start{};
    std::int32_t acc = cell.begin;
    for (std::size_t o = 0; o < 8; ++o) {
        start[o] = acc;
        acc += counts[o];
    }
    std::array<std::int32_t, 8> fill = start;
    for (std::int32_t k = cell.begin; k < cell.end; ++k) {
        std::int32_t const i = m_order[static_cast<std::size_t>(k)];
        scratch[static_cast<std::size_t>(fill[static_cast<std::size_t>(octant(i))]++)] = i;
    }
    std::copy(scratch.begin() + cell.begin, scratch.begin() + cell.end,
              m_order.begin() + cell.begin);

    auto const first = static_cast<std::int32_t>(m_nodes.size());
    std::int32_t children = 0;
    double const h = 0.5 * cell.half;
    for (std::size_t o = 0; o < 8; ++o) {
        if (counts[o] == 0)
            continue;
        TreeNode child;
        child.centre[0] = cell.centre[0] + ((o & 1U) != 0 ? h : -h);
        child.centre[1] = cell.centre[1] + ((o & 2U) != 0 ? h : -h);
        child.centre[2] = cell.centre[2] + ((o & 4U) != 0 ? h : -h);
        child.half = h;
        child.begin = start[o];
        child.end = start[o] + counts[o];
        child.level = cell.level + 1;
        m_nodes.push_back(child);
        ++children;
    }
    m_nodes[static_cast<std::size_t>(node)].firstChild = first;
    m_nodes[static_cast<std::size_t>(node)].childCount = children;
    for (std::int32_t c = 0; c < children; ++c)
        split(first + c, depth + 1, options, scratch, grains);
}

void Octree::computeMoments(OctreeBuildOptions const& options) {
    // Children always follow their parent, so a reverse sweep is a post-order traversal.
    for (std::size_t k = m_nodes.size(); k-- > 0;) {
        TreeNode& c = m_nodes[k];
        double mass = 0.0;
        double mx = 0.0;
        double my = 0.0;
        double mz = 0.0;
        if (c.childCount == 0) {
            for (auto i = static_cast<std::size_t>(c.begin); i < static_cast<std::size_t>(c.end);
                 ++i) {
                mass += m_m[i];
                mx += m_m[i] * m_x[i];
                my += m_m[i] * m_y[i];
                mz += m_m[i] * m_z[i];
            }
        } else {
            for (std::int32_t j = 0; j < c.childCount; ++j) {
                TreeNode const& s = m_nodes[static_cast<std::size_t>(c.firstChild + j)];
                mass += s.mass;
                mx += s.mass * s.com[0];
                my += s.mass * s.com[1];
                mz += s.mass * s.com[2];
            }
        }
        c.mass = mass;
        if (mass > 0.0) {
            c.com[0] = mx / mass;
            c.com[1] = my / mass;
            c.com[2] = mz / mass;
        } else { // massless cell: geometric centre
            std::copy(std::begin(c.centre), std::end(c.centre), std::begin(c.com));
        }
        double bmax = 0.0;
        std::fill(std::begin(c.quad), std::end(c.quad), 0.0);
        if (c.childCount == 0) {
            for (auto i = static_cast<std::size_t>(c.begin); i < static_cast<std::size_t>(c.end);
                 ++i) {
                double const dx = m_x[i] - c.com[0];
                double const dy = m_y[i] - c.com[1];
                double const dz = m_z[i] - c.com[2];
                bmax = std::max(bmax, std::sqrt(dx * dx + dy * dy + dz * dz));
                if (options.quadrupole)
                    addPointQuadrupole(c.quad, m_m[i], dx, dy, dz);
            }
        } else {
            // Exact b_max over the cell's grains (contiguous in tree order): the bound
            // max(b_child + |com_child - com|) overestimates it by up to ~50 %, which would
            // open cells needlessly. O(N) per tree level.
            for (auto i = static_cast<std::size_t>(c.begin); i < static_cast<std::size_t>(c.end);
                 ++i) {
                double const dx = m_x[i] - c.com[0];
                double const dy = m_y[i] - c.com[1];
                double const dz = m_z[i] - c.com[2];
                bmax = std::max(bmax, dx * dx + dy * dy + dz * dz);
            }
            bmax = std::sqrt(bmax);
            for (std::int32_t j = 0; j < c.childCount; ++j) {
                TreeNode const& s = m_nodes[static_cast<std::size_t>(c.firstChild + j)];
                double const dx = s.com[0] - c.com[0];
                double const dy = s.com[1] - c.com[1];
                double const dz = s.com[2] - c.com[2];
                if (options.quadrupole) {
                    for (int a = 0; a < 6; ++a)
                        c.quad[a] += s.quad[a]; // parallel-axis shift below
                    addPointQuadrupole(c.quad, s.mass, dx, dy, dz);
                }
            }
        }
        double const ox = c.com[0] - c.centre[0];
        double const oy = c.com[1] - c.centre[1];
        double const oz = c.com[2] - c.centre[2];
        double const offset = std::sqrt(ox * ox + oy * oy + oz * oz);
        // No grain is farther from the com than the farthest corner of the cube.
        c.bmax = std::min(bmax, offset + std::sqrt(3.0) * c.half);
        switch (options.criterion) {
        case OpeningCriterion::BmaxPlusOffset:
            c.rcrit = c.bmax / options.theta + offset;
            break;
        case OpeningCriterion::Bmax:
            c.rcrit = c.bmax / options.theta;
            break;
        case OpeningCriterion::EdgePlusOffset:
            c.rcrit = 2.0 * c.half / options.theta + offset;
            break;
        }
    }
}

} // namespace regolith::gravity::tree
