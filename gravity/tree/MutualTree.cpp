#include "gravity/tree/MutualTree.hpp"

#include "gravity/common/GatherAll.hpp"
#include "gravity/tree/Octree.hpp"

#include <array>
#include <cmath>
#include <vector>

namespace regolith::gravity::tree {

namespace {

/// The field a cell receives, as a Taylor expansion about its com: acceleration (3), tidal
/// tensor xx yy zz xy xz yz (6), potential (1).
struct CellField {
    std::array<double, 3> acc{};
    std::array<double, 6> tidal{};
    double phi = 0.0;
};

std::array<double, 3> symmetricTimes(std::array<double, 6> const& t, double x, double y, double z) {
    return {t[0] * x + t[3] * y + t[4] * z, t[3] * x + t[1] * y + t[5] * z,
            t[4] * x + t[5] * y + t[2] * z};
}

/// The dual-tree walk over one tree, accumulating into cell and grain fields.
class DualWalk {
public:
    DualWalk(Octree const& tree, TreeOptions const& o, MutualStats& stats)
        : m_tree(tree)
        , m_nodes(tree.nodes())
        , m_cells(tree.nodes().size())
        , m_ax(tree.x().size(), 0.0)
        , m_ay(tree.x().size(), 0.0)
        , m_az(tree.x().size(), 0.0)
        , m_phi(tree.x().size(), 0.0)
        , m_theta(o.theta)
        , m_G(o.G)
        , m_eps2(o.softening * o.softening)
        , m_stats(stats) {}

    void run() {
        if (!m_nodes.empty())
            self(0);
        passDown();
    }

    [[nodiscard]] std::vector<double> const& ax() const { return m_ax; }
    [[nodiscard]] std::vector<double> const& ay() const { return m_ay; }
    [[nodiscard]] std::vector<double> const& az() const { return m_az; }
    [[nodiscard]] std::vector<double> const& phi() const { return m_phi; }

private:
    /// Small cell pairs are cheaper grain by grain than as expansions.
    static constexpr long kDirectPairs = 24;

    [[nodiscard]] TreeNode const& node(std::int32_t k) const {
        return m_nodes[static_cast<std::size_t>(k)];
    }

    /// All interactions inside cell a.
    void self(std::int32_t a) {
        TreeNode const& c = node(a);
        if (c.childCount == 0) {
            for (std::int32_t i = c.begin; i < c.end; ++i)
                for (std::int32_t j = i + 1; j < c.end; ++j)
                    pair(i, j);
            m_stats.grainPair += static_cast<long long>(c.count()) * (c.count() - 1) / 2;
            return;
        }
        for (std::int32_t i = 0; i < c.childCount; ++i) {
            self(c.firstChild + i);
            for (std::int32_t j = i + 1; j < c.childCount; ++j)
                mutual(c.firstChild + i, c.firstChild + j);
        }
    }

    /// All interactions between disjoint cells a and b.
    void mutual(std::int32_t a, std::int32_t b) {
        TreeNode const& A = node(a);
        TreeNode const& B = node(b);
        double const dx = A.com[0] - B.com[0];
        double const dy = A.com[1] - B.com[1];
        double const dz = A.com[2] - B.com[2];
        double const r = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (m_theta * r > A.bmax + B.bmax && A.mass > 0.0 && B.mass > 0.0) {
            cellCell(a, b);
            return;
        }
        bool const aLeaf = A.childCount == 0;
        bool const bLeaf = B.childCount == 0;
        if ((aLeaf && bLeaf) || static_cast<long>(A.count()) * B.count() <= kDirectPairs) {
            for (std::int32_t i = A.begin; i < A.end; ++i)
                for (std::int32_t j = B.begin; j < B.end; ++j)
                    pair(i, j);
            m_stats.grainPair += static_cast<long long>(A.count()) * B.count();
            return;
        }
        if (aLeaf || (!bLeaf && B.bmax > A.bmax)) {
            for (std::int32_t k = 0; k < B.childCount; ++k)
                mutual(a, B.firstChild + k);
        } else {
            for (std::int32_t k = 0; k < A.childCount; ++k)
                mutual(A.firstChild + k, b);
        }
    }

    /// Grains i and j (tree order): one force, applied to both.
    void pair(std::int32_t i, std::int32_t j) {
        auto const u = static_cast<std::size_t>(i);
        auto const v = static_cast<std::size_t>(j);
        auto const x = m_tree.x();
        auto const y = m_tree.y();
        auto const z = m_tree.z();
        auto const m = m_tree.m();
        double const dx = x[u] - x[v];
        double const dy = y[u] - y[v];
        double const dz = z[u] - z[v];
        double const r2 = dx * dx + dy * dy + dz * dz;
        if (!(r2 > 0.0))
            return;
        double const inv = 1.0 / std::sqrt(r2 + m_eps2);
        double const g3 = m_G * inv * inv * inv;
        m_ax[u] -= g3 * m[v] * dx;
        m_ay[u] -= g3 * m[v] * dy;
        m_az[u] -= g3 * m[v] * dz;
        m_ax[v] += g3 * m[u] * dx;
        m_ay[v] += g3 * m[u] * dy;
        m_az[v] += g3 * m[u] * dz;
        m_phi[u] -= m_G * m[v] * inv;
        m_phi[v] -= m_G * m[u] * inv;
    }

    /// The mutual multipole interaction of cells a and b: F_A = -∂E/∂R, F_B = -F_A.
    void cellCell(std::int32_t a, std::int32_t b) {
        ++m_stats.cellCell;
        TreeNode const& A = node(a);
        TreeNode const& B = node(b);
        double const rx = A.com[0] - B.com[0];
        double const ry = A.com[1] - B.com[1];
        double const rz = A.com[2] - B.com[2];
        double const r2 = rx * rx + ry * ry + rz * rz + m_eps2;
        double const inv = 1.0 / std::sqrt(r2);
        double const inv2 = inv * inv;
        double const inv3 = inv * inv2;
        double const inv5 = inv3 * inv2;
        std::array<double, 6> qe{};
        for (std::size_t k = 0; k < 6; ++k)
            qe[k] = A.mass * B.quad[k] + B.mass * A.quad[k];
        auto const qr = symmetricTimes(qe, rx, ry, rz);
        double const rqr = rx * qr[0] + ry * qr[1] + rz * qr[2];
        double const radial = A.mass * B.mass * inv3 + 2.5 * rqr * inv5 * inv2;
        std::array<double, 3> const force{m_G * (qr[0] * inv5 - radial * rx),
                                          m_G * (qr[1] * inv5 - radial * ry),
                                          m_G * (qr[2] * inv5 - radial * rz)};
        CellField& fa = m_cells[static_cast<std::size_t>(a)];
        CellField& fb = m_cells[static_cast<std::size_t>(b)];
        for (std::size_t k = 0; k < 3; ++k) {
            fa.acc[k] += force[k] / A.mass;
            fb.acc[k] -= force[k] / B.mass;
        }
        // Tidal tensor of a unit monopole: K = -G (I / r³ - 3 R Rᵀ / r⁵).
        std::array<double, 6> const kt{
            -m_G * (inv3 - 3.0 * rx * rx * inv5), -m_G * (inv3 - 3.0 * ry * ry * inv5),
            -m_G * (inv3 - 3.0 * rz * rz * inv5), m_G * 3.0 * rx * ry * inv5,
            m_G * 3.0 * rx * rz * inv5,           m_G * 3.0 * ry * rz * inv5};
        for (std::size_t k = 0; k < 6; ++k) {
            fa.tidal[k] += B.mass * kt[k];
            fb.tidal[k] += A.mass * kt[k];
        }
        auto const qbr = symmetricTimes(
            {B.quad[0], B.quad[1], B.quad[2], B.quad[3], B.quad[4], B.quad[5]}, rx, ry, rz);
        auto const qar = symmetricTimes(
            {A.quad[0], A.quad[1], A.quad[2], A.quad[3], A.quad[4], A.quad[5]}, rx, ry, rz);
        fa.phi -= m_G * (B.mass * inv + 0.5 * (rx * qbr[0] + ry * qbr[1] + rz * qbr[2]) * inv5);
        fb.phi -= m_G * (A.mass * inv + 0.5 * (rx * qar[0] + ry * qar[1] + rz * qar[2]) * inv5);
    }

    /// Parents precede children: one forward sweep shifts every expansion to the children
    /// and, at the leaves, evaluates it at the grains.
    void passDown() {
        auto const x = m_tree.x();
        auto const y = m_tree.y();
        auto const z = m_tree.z();
        for (std::size_t k = 0; k < m_nodes.size(); ++k) {
            TreeNode const& c = m_nodes[k];
            CellField const f = m_cells[k];
            auto const shift = [&](double dx, double dy, double dz) {
                auto const t = symmetricTimes(f.tidal, dx, dy, dz);
                return std::array<double, 4>{f.acc[0] + t[0], f.acc[1] + t[1], f.acc[2] + t[2],
                                             f.phi -
                                                 (f.acc[0] * dx + f.acc[1] * dy + f.acc[2] * dz)};
            };
            if (c.childCount == 0) {
                for (auto i = static_cast<std::size_t>(c.begin);
                     i < static_cast<std::size_t>(c.end); ++i) {
                    auto const s = shift(x[i] - c.com[0], y[i] - c.com[1], z[i] - c.com[2]);
                    m_ax[i] += s[0];
                    m_ay[i] += s[1];
                    m_az[i] += s[2];
                    m_phi[i] += s[3];
                }
                continue;
            }
            for (std::int32_t j = 0; j < c.childCount; ++j) {
                auto const ck = static_cast<std::size_t>(c.firstChild + j);
                TreeNode const& ch = m_nodes[ck];
                auto const s =
                    shift(ch.com[0] - c.com[0], ch.com[1] - c.com[1], ch.com[2] - c.com[2]);
                CellField& g = m_cells[ck];
                for (std::size_t a = 0; a < 3; ++a)
                    g.acc[a] += s[a];
                g.phi += s[3];
                for (std::size_t a = 0; a < 6; ++a)
                    g.tidal[a] += f.tidal[a];
            }
        }
    }

    Octree const& m_tree;
    std::vector<TreeNode> const& m_nodes;
    std::vector<CellField> m_cells;
    std::vector<double> m_ax, m_ay, m_az, m_phi;
    double m_theta;
    double m_G;
    double m_eps2;
    MutualStats& m_stats;
};

} // namespace

MutualTree::MutualTree(TreeOptions const& options)
    : m_options(options) {
    validate(m_options);
}

double MutualTree::evaluate(PointMasses const& grains, FieldOut out) {
    validatePointMasses(grains, "gravity");
    validateFieldOut(out, grains.size());
    m_stats = {};
    Octree const tree = Octree::build(grains, {m_options.leafSize, 0.0, m_options.theta,
                                               m_options.quadrupole, m_options.criterion});
    DualWalk walk(tree, m_options, m_stats);
    walk.run();
    double energy = 0.0;
    for (std::size_t k = 0; k < grains.size(); ++k) {
        auto const i = static_cast<std::size_t>(tree.order()[k]);
        out.ax[i] = walk.ax()[k];
        out.ay[i] = walk.ay()[k];
        out.az[i] = walk.az()[k];
        if (!out.phi.empty())
            out.phi[i] = walk.phi()[k];
        energy += 0.5 * grains.m[i] * walk.phi()[k];
    }
    return energy;
}

double MutualTree::evaluateGathered(core::Comm const& comm, PointMasses const& local,
                                    FieldOut out) {
    validatePointMassesCollective(comm, local, "gravity");
    validateFieldOut(out, local.size());
    OwnedMasses const all = gatherAll(comm, local);
    std::size_t const n = all.x.size();
    std::vector<double> ax(n), ay(n), az(n), phi(n);
    double const energy = evaluate({all.x, all.y, all.z, all.m}, {ax, ay, az, phi});
    // This rank's grains start after those of the ranks before it.
    std::vector<int> const counts = comm.allGather(static_cast<int>(local.size()));
    std::size_t offset = 0;
    for (int r = 0; r < comm.rank(); ++r)
        offset += static_cast<std::size_t>(counts[static_cast<std::size_t>(r)]);
    for (std::size_t i = 0; i < local.size(); ++i) {
        out.ax[i] = ax[offset + i];
        out.ay[i] = ay[offset + i];
        out.az[i] = az[offset + i];
        if (!out.phi.empty())
            out.phi[i] = phi[offset + i];
    }
    return energy;
}

} // namespace regolith::gravity::tree
