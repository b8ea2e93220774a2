#include "gravity/tree/InteractionList.hpp"

#include "gravity/common/SimdClones.hpp"

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

namespace {

/// The list kernel (see InteractionList::evaluate); compiled for AVX2 + FMA and baseline.
REGOLITH_SIMD_CLONES
void evaluateListKernel(double const* tx, double const* ty, double const* tz, std::size_t n,
                        double G, double eps2, double* ax, double* ay, double* az, double* phi,
                        double const* px, double const* py, double const* pz, double const* pm,
                        std::size_t np, double const* cx, double const* cy, double const* cz,
                        double const* cm, double const* qxx, double const* qyy, double const* qzz,
                        double const* qxy, double const* qxz, double const* qyz, std::size_t nc) {
    // One target at a time, the list streaming past: the sums stay in registers and the
    // loop over the list vectorises as a SIMD reduction (-fopenmp-simd).
    for (std::size_t i = 0; i < n; ++i) {
        double const x = tx[i];
        double const y = ty[i];
        double const z = tz[i];
        double sx = 0.0;
        double sy = 0.0;
        double sz = 0.0;
        double sp = 0.0;
#pragma omp simd reduction(+ : sx, sy, sz, sp)
        for (std::size_t j = 0; j < np; ++j) {
            double const dx = px[j] - x;
            double const dy = py[j] - y;
            double const dz = pz[j] - z;
            double const r2 = dx * dx + dy * dy + dz * dz;
            double const inv = r2 > 0.0 ? 1.0 / std::sqrt(r2 + eps2) : 0.0;
            double const mi = pm[j] * inv;
            double const f = mi * inv * inv;
            sx += f * dx;
            sy += f * dy;
            sz += f * dz;
            sp += mi;
        }
#pragma omp simd reduction(+ : sx, sy, sz, sp)
        for (std::size_t j = 0; j < nc; ++j) {
            // r = x - com; the sums hold a/G and -φ/G.
            double const rx = x - cx[j];
            double const ry = y - cy[j];
            double const rz = z - cz[j];
            double const r2 = rx * rx + ry * ry + rz * rz + eps2;
            double const inv = 1.0 / std::sqrt(r2);
            double const inv2 = inv * inv;
            double const inv3 = inv * inv2;
            double const inv5 = inv3 * inv2;
            double const qrx = qxx[j] * rx + qxy[j] * ry + qxz[j] * rz;
            double const qry = qxy[j] * rx + qyy[j] * ry + qyz[j] * rz;
            double const qrz = qxz[j] * rx + qyz[j] * ry + qzz[j] * rz;
            double const rqr = rx * qrx + ry * qry + rz * qrz;
            double const radial = cm[j] * inv3 + 2.5 * rqr * inv5 * inv2;
            sx += qrx * inv5 - radial * rx;
            sy += qry * inv5 - radial * ry;
            sz += qrz * inv5 - radial * rz;
            sp += cm[j] * inv + 0.5 * rqr * inv5;
        }
        ax[i] += G * sx;
        ay[i] += G * sy;
        az[i] += G * sz;
        phi[i] -= G * sp;
    }
}

} // namespace

void InteractionList::evaluate(double const* tx, double const* ty, double const* tz, std::size_t n,
                               double G, double eps2, double* ax, double* ay, double* az,
                               double* phi) const {
    evaluateListKernel(tx, ty, tz, n, G, eps2, ax, ay, az, phi, m_px.data(), m_py.data(),
                       m_pz.data(), m_pm.data(), m_px.size(), m_cx.data(), m_cy.data(), m_cz.data(),
                       m_cm.data(), m_qxx.data(), m_qyy.data(), m_qzz.data(), m_qxy.data(),
                       m_qxz.data(), m_qyz.data(), m_cx.size());
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
