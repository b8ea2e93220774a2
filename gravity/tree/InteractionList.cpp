#include "gravity/tree/InteractionList.hpp"

#include <cmath>

namespace regolith::gravity::tree {

void InteractionList::clear() {
    for (auto* v : {&m_cx, &m_cy, &m_cz, &m_cm, &m_qxx, &m_qyy, &m_qzz, &m_qxy, &m_qxz, &m_qyz,
                    &m_px, &m_py, &m_pz, &m_pm})
        v->clear();
}

void InteractionList::addCell(TreeNode const& c, bool quadrupole) {
    if (!quadrupole) {
        m_px.push_back(c.com[0]);
        m_py.push_back(c.com[1]);
        m_pz.push_back(c.com[2]);
        m_pm.push_back(c.mass);
        return;
    }
    m_cx.push_back(c.com[0]);
    m_cy.push_back(c.com[1]);
    m_cz.push_back(c.com[2]);
    m_cm.push_back(c.mass);
    m_qxx.push_back(c.quad[0]);
    m_qyy.push_back(c.quad[1]);
    m_qzz.push_back(c.quad[2]);
    m_qxy.push_back(c.quad[3]);
    m_qxz.push_back(c.quad[4]);
    m_qyz.push_back(c.quad[5]);
}

void InteractionList::addGrains(TreeView const& t, std::int32_t begin, std::int32_t end) {
    auto const b = static_cast<std::size_t>(begin);
    auto const e = static_cast<std::size_t>(end);
    m_px.insert(m_px.end(), t.x.begin() + static_cast<long>(b), t.x.begin() + static_cast<long>(e));
    m_py.insert(m_py.end(), t.y.begin() + static_cast<long>(b), t.y.begin() + static_cast<long>(e));
    m_pz.insert(m_pz.end(), t.z.begin() + static_cast<long>(b), t.z.begin() + static_cast<long>(e));
    m_pm.insert(m_pm.end(), t.m.begin() + static_cast<long>(b), t.m.begin() + static_cast<long>(e));
}

void InteractionList::evaluate(double const* tx, double const* ty, double const* tz, std::size_t n,
                               double G, double eps2, double* ax, double* ay, double* az,
                               double* phi) const {
    for (std::size_t j = 0; j < m_px.size(); ++j) {
        double const xj = m_px[j];
        double const yj = m_py[j];
        double const zj = m_pz[j];
        double const gm = G * m_pm[j];
        for (std::size_t i = 0; i < n; ++i) {
            double const dx = xj - tx[i];
            double const dy = yj - ty[i];
            double const dz = zj - tz[i];
            double const r2 = dx * dx + dy * dy + dz * dz;
            bool const valid = r2 > 0.0;
            double const inv = valid ? 1.0 / std::sqrt(r2 + eps2) : 0.0;
            double const f = gm * inv * inv * inv;
            ax[i] += f * dx;
            ay[i] += f * dy;
            az[i] += f * dz;
            phi[i] -= gm * inv;
        }
    }
    for (std::size_t j = 0; j < m_cx.size(); ++j) {
        double const cx = m_cx[j];
        double const cy = m_cy[j];
        double const cz = m_cz[j];
        double const gm = G * m_cm[j];
        double const qxx = G * m_qxx[j];
        double const qyy = G * m_qyy[j];
        double const qzz = G * m_qzz[j];
        double const qxy = G * m_qxy[j];
        double const qxz = G * m_qxz[j];
        double const qyz = G * m_qyz[j];
        for (std::size_t i = 0; i < n; ++i) {
            double const rx = tx[i] - cx;
            double const ry = ty[i] - cy;
            double const rz = tz[i] - cz;
            double const r2 = rx * rx + ry * ry + rz * rz + eps2;
            double const inv = 1.0 / std::sqrt(r2);
            double const inv2 = inv * inv;
            double const inv3 = inv * inv2;
            double const inv5 = inv3 * inv2;
            double const qrx = qxx * rx + qxy * ry + qxz * rz;
            double const qry = qxy * rx + qyy * ry + qyz * rz;
            double const qrz = qxz * rx + qyz * ry + qzz * rz;
            double const rqr = rx * qrx + ry * qry + rz * qrz;
            double const radial = gm * inv3 + 2.5 * rqr * inv5 * inv2;
            ax[i] += qrx * inv5 - radial * rx;
            ay[i] += qry * inv5 - radial * ry;
            az[i] += qrz * inv5 - radial * rz;
            phi[i] -= gm * inv + 0.5 * rqr * inv5;
        }
    }
}

void collectInteractions(TreeView const& tree, core::AABB const& group, bool quadrupole,
                         InteractionList& list, std::vector<std::int32_t>& stack) {
    if (tree.nodes.empty())
        return;
    stack.clear();
    stack.push_back(0);
    while (!stack.empty()) {
        TreeNode const& c = tree.nodes[static_cast<std::size_t>(stack.back())];
        stack.pop_back();
        core::Vec3 const com(c.com[0], c.com[1], c.com[2]);
        if (c.closed != 0 || group.sqDistance(com) > c.rcrit * c.rcrit) {
            list.addCell(c, quadrupole);
        } else if (c.childCount == 0) {
            list.addGrains(tree, c.begin, c.end);
        } else {
            for (std::int32_t k = c.childCount; k-- > 0;)
                stack.push_back(c.firstChild + k);
        }
    }
}

} // namespace regolith::gravity::tree
