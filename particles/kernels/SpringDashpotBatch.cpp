#include "particles/kernels/SpringDashpotBatch.hpp"

#include "core/Error.hpp"
#include "particles/kernels/SpringDashpotLanes.hpp"

#include <cmath>

namespace regolith::particles {

void SpringDashpotBatch::add(PairOverlap const& p, HistoryEntry& entry, std::uint8_t hint,
                             HistoryEntry* rolling) {
    std::size_t const k = m_size++;
    std::size_t const i = p.i, j = p.j;
    m_i[k] = static_cast<std::uint32_t>(i);
    m_j[k] = static_cast<std::uint32_t>(j);
    m_hint[k] = hint;
    m_entry[k] = &entry;
    m_shift[0][k] = p.shiftJ.x();
    m_shift[1][k] = p.shiftJ.y();
    m_shift[2][k] = p.shiftJ.z();
    m_s[0][k] = entry.spring.x();
    m_s[1][k] = entry.spring.y();
    m_s[2][k] = entry.spring.z();
    m_rollingEntry[k] = rolling;
    m_kept[k] = nullptr;
    if (rolling) { // model C: every pair has one (only Rolling::Spring reads the lanes)
        m_r[0][k] = rolling->spring.x();
        m_r[1][k] = rolling->spring.y();
        m_r[2][k] = rolling->spring.z();
    }
}

using spring_lanes::cross;
using spring_lanes::loadTransposed;

void SpringDashpotBatch::loadCentres(ParticleStorage const& ps) {
    std::size_t const n = m_size;
    for (std::size_t k = n; k % 8 != 0; ++k) {
        m_i[k] = m_i[0];
        m_j[k] = m_j[0];
    }
    double const* const x = ps.positions().data()->data();
    for (std::size_t b = 0; b < n; b += 8) {
        loadTransposed(x, &m_i[b], &m_xi[0][b], &m_xi[1][b], &m_xi[2][b]);
        loadTransposed(x, &m_j[b], &m_xj[0][b], &m_xj[1][b], &m_xj[2][b]);
    }
}

void SpringDashpotBatch::evaluate(ParticleStorage const& ps, SpringDashpot const& model,
                                  double dt) {
    std::size_t const n = m_size;
    if (n == 0)
        return; // (an empty block's storage has no arrays to point into)
    loadCentres(ps);
    auto const& materials = model.materials();
    // One material (most scenes): the parameters are the same in every lane, so the lanes
    // read them as constants; several: gathered per contact from the tables.
    bool const uniform = materials.numTypes() == 1;
    LinearContactParams const& one = materials(0, 0);
    Parameters const uniformParameters = spring_lanes::parametersOf(model, 0, 0);
    if (!uniform) {
        for (std::size_t k = 0; k < n; ++k) {
            std::uint32_t const a = ps.type(m_i[k]), b = ps.type(m_j[k]);
            m_parameters.set(k, spring_lanes::parametersOf(model, a, b));
        }
    }
    // Rolling resistance costs a root and two divisions per lane (model C three of each and
    // the spring's projection); a batch without it (most scenes: rolling friction 0) skips
    // them, with the same bits (its torque is then + 0.0).
    bool rolling = uniform && one.rollingFriction > 0.0;
    for (std::size_t k = 0; !uniform && k < n; ++k)
        rolling = rolling || m_parameters.muRoll[k] > 0.0;
    Rolling const law = model.hasRollingSpring() ? Rolling::Spring
                        : rolling                ? Rolling::Constant
                                                 : Rolling::None;
    // The velocities and spins, eight contacts at a time.
    double const* const v = ps.velocities().data()->data();
    double const* const w = ps.angularVelocities().data()->data();
    for (std::size_t b = 0; b < n; b += 8) {
        loadTransposed(v, &m_i[b], &m_vi[0][b], &m_vi[1][b], &m_vi[2][b]);
        loadTransposed(v, &m_j[b], &m_vj[0][b], &m_vj[1][b], &m_vj[2][b]);
        loadTransposed(w, &m_i[b], &m_wi[0][b], &m_wi[1][b], &m_wi[2][b]);
        loadTransposed(w, &m_j[b], &m_wj[0][b], &m_wj[1][b], &m_wj[2][b]);
    }
    GrainScalars const g = GrainScalars::of(ps);
    auto const run = [&]<Rolling kLaw>() {
        if (uniform)
            evaluateLanes<kLaw, true>(g, uniformParameters, dt);
        else
            evaluateLanes<kLaw, false>(g, uniformParameters, dt);
    };
    switch (law) {
    case Rolling::None:
        run.template operator()<Rolling::None>();
        break;
    case Rolling::Constant:
        run.template operator()<Rolling::Constant>();
        break;
    case Rolling::Spring:
        run.template operator()<Rolling::Spring>();
        break;
    }
}

template <SpringDashpotBatch::Rolling kRolling, bool kUniform>
void SpringDashpotBatch::evaluateLanes(GrainScalars g, Parameters const uniform, double dt) {
    std::size_t const n = m_size;
    double const* __restrict const invM = g.invM;
    double const* __restrict const invI = g.invI;
    double const* __restrict const rad = g.rad;
    // One contact per iteration, no calls, every operation done in every lane and the scalar
    // code's branches as selects between the results: the loop GCC vectorises (this file is
    // compiled with -fno-trapping-math, which lets it evaluate a division or root whose result
    // a lane then discards; the bits of the results kept are the same). The comments name the
    // scalar code each part mirrors (same operations, same order).
    for (std::size_t k = 0; k < n; ++k) {
        double const xix = m_xi[0][k], xiy = m_xi[1][k], xiz = m_xi[2][k];
        double const xjx = m_xj[0][k] + m_shift[0][k], xjy = m_xj[1][k] + m_shift[1][k],
                     xjz = m_xj[2][k] + m_shift[2][k];
        double const a = rad[m_i[k]], b = rad[m_j[k]];
        // overlapGeometry: normal, penetration, point; the lever arms as pairState takes them.
        double const dx = xjx - xix, dy = xjy - xiy, dz = xjz - xiz;
        double const dist = std::sqrt(dx * dx + dy * dy + dz * dz);
        bool const apart = dist > 0.0;
        double const nx = apart ? dx / dist : 0.0, ny = apart ? dy / dist : 0.0,
                     nz = apart ? dz / dist : 1.0;
        double const pen = (a + b) - dist;
        double const toPoint = a - 0.5 * pen;
        double const pointX = xix + toPoint * nx, pointY = xiy + toPoint * ny,
                     pointZ = xiz + toPoint * nz;
        double const rix = pointX - xix, riy = pointY - xiy, riz = pointZ - xiz;
        double const rjx = pointX - xjx, rjy = pointY - xjy, rjz = pointZ - xjz;
        double const wix = m_wi[0][k], wiy = m_wi[1][k], wiz = m_wi[2][k];
        double const wjx = m_wj[0][k], wjy = m_wj[1][k], wjz = m_wj[2][k];
        // pairState: v + w x r at the contact point, relative velocity and spin, m_eff, R_eff.
        double const vix = m_vi[0][k] + cross(0, wix, wiy, wiz, rix, riy, riz);
        double const viy = m_vi[1][k] + cross(1, wix, wiy, wiz, rix, riy, riz);
        double const viz = m_vi[2][k] + cross(2, wix, wiy, wiz, rix, riy, riz);
        double const vjx = m_vj[0][k] + cross(0, wjx, wjy, wjz, rjx, rjy, rjz);
        double const vjy = m_vj[1][k] + cross(1, wjx, wjy, wjz, rjx, rjy, rjz);
        double const vjz = m_vj[2][k] + cross(2, wjx, wjy, wjz, rjx, rjy, rjz);
        double const ux = vjx - vix, uy = vjy - viy, uz = vjz - viz;
        double const ox = wjx - wix, oy = wjy - wiy, oz = wjz - wiz;
        double const meff = 1.0 / (invM[m_i[k]] + invM[m_j[k]]);
        double const reff = a * b / (a + b);
        double const invIsum = invI[m_i[k]] + invI[m_j[k]];
        // SpringDashpot::operator() with the pair's parameters.
        Parameters const p = kUniform ? uniform : m_parameters.at(k);
        spring_lanes::LaneState const q{nx, ny, nz, pen,  ux,   uy,     uz,
                                        ox, oy, oz, meff, reff, invIsum};
        double sx = m_s[0][k], sy = m_s[1][k], sz = m_s[2][k];
        double rx = 0.0, ry = 0.0, rz = 0.0;
        if constexpr (kRolling == Rolling::Spring) {
            rx = m_r[0][k];
            ry = m_r[1][k];
            rz = m_r[2][k];
        }
        double fx, fy, fz, mx, my, mz;
        spring_lanes::springDashpot<kRolling>(q, p, dt, sx, sy, sz, rx, ry, rz, m_rOut[0][k],
                                              m_rOut[1][k], m_rOut[2][k], fx, fy, fz, mx, my, mz);
        m_s[0][k] = sx;
        m_s[1][k] = sy;
        m_s[2][k] = sz;
        // evaluatePair: the torques about each centre.
        m_f[0][k] = fx;
        m_f[1][k] = fy;
        m_f[2][k] = fz;
        m_tj[0][k] = cross(0, rjx, rjy, rjz, fx, fy, fz) + mx;
        m_tj[1][k] = cross(1, rjx, rjy, rjz, fx, fy, fz) + my;
        m_tj[2][k] = cross(2, rjx, rjy, rjz, fx, fy, fz) + mz;
        m_ti[0][k] = cross(0, rix, riy, riz, fx, fy, fz) + mx;
        m_ti[1][k] = cross(1, rix, riy, riz, fx, fy, fz) + my;
        m_ti[2][k] = cross(2, rix, riy, riz, fx, fy, fz) + mz;
    }
}

} // namespace regolith::particles
