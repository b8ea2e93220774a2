#include "particles/kernels/SpringDashpotBatch.hpp"

#include "core/Error.hpp"
#include "particles/storage/TransposedLoads.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

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

namespace {

#if defined(__AVX512VL__)
// Vector types for the 512-bit shuffles; only where the build has AVX-512 (without it GCC
// splits them into element moves through the stack).
using Vector4 = double __attribute__((vector_size(32)));
using Vector8 = double __attribute__((vector_size(64)));
#endif

/// The Vec3s at base + 3 idx[0..7] transposed into eight x, y and z lanes, without reading past
/// z_k (the last copy's Vec3 ends its array) and without a store a later load must merge
/// (partial stores stall the lane loop's loads on store forwarding).
[[gnu::always_inline]] inline void loadTransposed(double const* base, std::uint32_t const* idx,
                                                  double* x, double* y, double* z) {
#if defined(__AVX512VL__)
    // Eight loads and eleven shuffles over 512 bits, where a gather per component cost ~2.5x more.
    Vector4 r[8]; // r[k] = (x_k y_k z_k 0); no function returns a vector (an ABI without AVX)
    for (int k = 0; k < 8; ++k)
        r[k] = std::bit_cast<Vector4>(_mm256_maskz_loadu_pd(0x7, base + 3 * std::size_t{idx[k]}));
    Vector8 a[4]; // a[k] = (x_k y_k z_k 0 x_k+4 y_k+4 z_k+4 0)
    for (int k = 0; k < 4; ++k)
        a[k] = __builtin_shufflevector(r[k], r[k + 4], 0, 1, 2, 3, 4, 5, 6, 7);
    Vector8 const xz01 = __builtin_shufflevector(a[0], a[1], 0, 8, 2, 10, 4, 12, 6, 14);
    Vector8 const y01 = __builtin_shufflevector(a[0], a[1], 1, 9, 3, 11, 5, 13, 7, 15);
    Vector8 const xz23 = __builtin_shufflevector(a[2], a[3], 0, 8, 2, 10, 4, 12, 6, 14);
    Vector8 const y23 = __builtin_shufflevector(a[2], a[3], 1, 9, 3, 11, 5, 13, 7, 15);
    Vector8 const vx = __builtin_shufflevector(xz01, xz23, 0, 1, 8, 9, 4, 5, 12, 13);
    Vector8 const vy = __builtin_shufflevector(y01, y23, 0, 1, 8, 9, 4, 5, 12, 13);
    Vector8 const vz = __builtin_shufflevector(xz01, xz23, 2, 3, 10, 11, 6, 7, 14, 15);
    std::memcpy(x, &vx, sizeof vx);
    std::memcpy(y, &vy, sizeof vy);
    std::memcpy(z, &vz, sizeof vz);
#else
    // Two 4 x 4 transposes (the 512-bit shuffles above, split by GCC into element moves
    // through the stack, made the kernel ~2.7x slower without AVX-512).
    lane_loads::transposed4(base, idx, x, y, z);
    lane_loads::transposed4(base, idx + 4, x + 4, y + 4, z + 4);
#endif
}

/// a x b, component `c`, in Eigen's order of operations.
inline double cross(int c, double ax, double ay, double az, double bx, double by, double bz) {
    return c == 0 ? ay * bz - az * by : (c == 1 ? az * bx - ax * bz : ax * by - ay * bx);
}

/// tangentialForce (with projectSpring) in one lane, branch-free: rotates the spring s into the
/// plane normal to n keeping its length, grows it by v dt, and returns the force -k s - c v
/// capped at `limit` (the spring truncated to match), all zero unless k > 0 and limit > 0.
/// The same operations in the same order as the scalar code: the tangential spring and model
/// C's rolling spring both go through it.
[[gnu::always_inline]] inline void springSlider(double& sx, double& sy, double& sz, double nx,
                                                double ny, double nz, double vx, double vy,
                                                double vz, double k, double c, double limit,
                                                double dt, double& fx, double& fy, double& fz) {
    double const before = sx * sx + sy * sy + sz * sz;
    double const along = sx * nx + sy * ny + sz * nz;
    double const px = sx - along * nx, py = sy - along * ny, pz = sz - along * nz;
    double const after = px * px + py * py + pz * pz;
    bool const keepLength = after > 1e-24 * before;
    double const scale = std::sqrt(before / after); // used where keepLength only
    bool const projected = before != 0.0;
    double ux = projected ? (keepLength ? px * scale : 0.0) : sx;
    double uy = projected ? (keepLength ? py * scale : 0.0) : sy;
    double uz = projected ? (keepLength ? pz * scale : 0.0) : sz;
    ux += vx * dt;
    uy += vy * dt;
    uz += vz * dt;
    double tx = -k * ux - c * vx, ty = -k * uy - c * vy, tz = -k * uz - c * vz;
    double const f2 = tx * tx + ty * ty + tz * tz;
    bool const slides = f2 > limit * limit;
    double const cut = limit / std::sqrt(f2); // used where slides only
    double const cx = tx * cut, cy = ty * cut, cz = tz * cut;
    double const wx = -(cx + c * vx) / k, wy = -(cy + c * vy) / k, wz = -(cz + c * vz) / k;
    ux = slides ? wx : ux;
    uy = slides ? wy : uy;
    uz = slides ? wz : uz;
    tx = slides ? cx : tx;
    ty = slides ? cy : ty;
    tz = slides ? cz : tz;
    bool const active = k > 0.0 && limit > 0.0;
    fx = active ? tx : 0.0;
    fy = active ? ty : 0.0;
    fz = active ? tz : 0.0;
    sx = active ? ux : 0.0;
    sy = active ? uy : 0.0;
    sz = active ? uz : 0.0;
}
} // namespace

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
    auto const parameters = [&model](LinearContactParams const& p, std::uint32_t a,
                                     std::uint32_t b) {
        return Parameters{p.stiffness,
                          p.tangentialStiffness,
                          model.dampingRatio(a, b),
                          p.friction,
                          p.tangentialDampingRatio,
                          p.rollingFriction,
                          p.rollingSpring.enabled ? 1.0 : 0.0,
                          p.rollingSpring.stiffness,
                          p.rollingSpring.dampingRatio};
    };
    Parameters const uniformParameters = parameters(one, 0, 0);
    if (!uniform) {
        for (std::size_t k = 0; k < n; ++k) {
            std::uint32_t const a = ps.type(m_i[k]), b = ps.type(m_j[k]);
            Parameters const p = parameters(materials(a, b), a, b);
            m_k[k] = p.k;
            m_kt[k] = p.kt;
            m_ratio[k] = p.ratio;
            m_mu[k] = p.mu;
            m_ctRatio[k] = p.ctRatio;
            m_muRoll[k] = p.muRoll;
            m_spring[k] = p.spring;
            m_kr[k] = p.kr;
            m_etaR[k] = p.etaR;
        }
    }
    // Rolling resistance costs a root and two divisions per lane (model C three of each and
    // the spring's projection); a batch without it (most scenes: rolling friction 0) skips
    // them, with the same bits (its torque is then + 0.0).
    bool rolling = uniform && one.rollingFriction > 0.0;
    for (std::size_t k = 0; !uniform && k < n; ++k)
        rolling = rolling || m_muRoll[k] > 0.0;
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
        double const kn = kUniform ? uniform.k : m_k[k], kt = kUniform ? uniform.kt : m_kt[k];
        double const ratio = kUniform ? uniform.ratio : m_ratio[k];
        double const mu = kUniform ? uniform.mu : m_mu[k];
        double const ctRatio = kUniform ? uniform.ctRatio : m_ctRatio[k];
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
        [[maybe_unused]] double const ox = wjx - wix, oy = wjy - wiy, oz = wjz - wiz;
        double const meff = 1.0 / (invM[m_i[k]] + invM[m_j[k]]);
        [[maybe_unused]] double const reff = a * b / (a + b);
        [[maybe_unused]] double const invIsum = invI[m_i[k]] + invI[m_j[k]];
        // SpringDashpot::operator(): normal force.
        double const cn = 2.0 * ratio * std::sqrt(kn * meff);
        double const vn = ux * nx + uy * ny + uz * nz;
        double const vtx = ux - vn * nx, vty = uy - vn * ny, vtz = uz - vn * nz;
        double const fn = kn * pen - cn * vn;
        double const ct = ctRatio * cn;
        double const limit = mu * (fn < 0.0 ? 0.0 : fn); // std::max(fn, 0.0)
        // tangentialForce: projectSpring, grow, trial force, Coulomb limit.
        double sx = m_s[0][k], sy = m_s[1][k], sz = m_s[2][k];
        double tx, ty, tz;
        springSlider(sx, sy, sz, nx, ny, nz, vtx, vty, vtz, kt, ct, limit, dt, tx, ty, tz);
        m_s[0][k] = sx;
        m_s[1][k] = sy;
        m_s[2][k] = sz;
        double const fx = fn * nx + tx, fy = fn * ny + ty, fz = fn * nz + tz;
        // rollingResistance (+0.0 where it does not roll, as the scalar code adds).
        double mx = 0.0, my = 0.0, mz = 0.0;
        if constexpr (kRolling != Rolling::None) {
            double const muRoll = kUniform ? uniform.muRoll : m_muRoll[k];
            // rollingTorque (model A).
            double const spin = ox * nx + oy * ny + oz * nz;
            double const qx = ox - spin * nx, qy = oy - spin * ny, qz = oz - spin * nz;
            double const qNorm = std::sqrt(qx * qx + qy * qy + qz * qz);
            double magnitude = muRoll * reff * fn;
            double const stop = qNorm / (dt * invIsum);
            magnitude = invIsum > 0.0 && stop < magnitude ? stop : magnitude; // std::min
            double const rolling = -magnitude / qNorm; // used where rolls only
            bool const rolls = muRoll > 0.0 && fn > 0.0 && qNorm != 0.0;
            mx = rolls ? rolling * qx : 0.0;
            my = rolls ? rolling * qy : 0.0;
            mz = rolls ? rolling * qz : 0.0;
            if constexpr (kRolling == Rolling::Spring) {
                // rollingSpringTorque (model C) where the pair has it.
                bool const spring = (kUniform ? uniform.spring : m_spring[k]) != 0.0;
                double const krLaw = kUniform ? uniform.kr : m_kr[k];
                double const etaR = kUniform ? uniform.etaR : m_etaR[k];
                double const krTrial = krLaw > 0.0 ? krLaw : 2.25 * muRoll * muRoll * kn;
                double const kr = kn < krTrial ? kn : krTrial; // std::min(krTrial, kn)
                double const vrx = reff * cross(0, ox, oy, oz, nx, ny, nz);
                double const vry = reff * cross(1, ox, oy, oz, nx, ny, nz);
                double const vrz = reff * cross(2, ox, oy, oz, nx, ny, nz);
                double const rr = reff * reff * invIsum;
                double const damped = 2.0 * etaR * std::sqrt(3.5 * kr / rr);
                double const stopRolling = 1.0 / (rr * dt);
                double const cr = invIsum > 0.0
                                      ? (stopRolling < damped ? stopRolling : damped) // std::min
                                      : 0.0;
                double const limitRolling = muRoll * (fn < 0.0 ? 0.0 : fn); // std::max(fn, 0.0)
                double const r0x = m_r[0][k], r0y = m_r[1][k], r0z = m_r[2][k];
                double rx = r0x, ry = r0y, rz = r0z;
                double gx, gy, gz;
                springSlider(rx, ry, rz, nx, ny, nz, vrx, vry, vrz, kr, cr, limitRolling, dt, gx,
                             gy, gz);
                mx = spring ? reff * cross(0, nx, ny, nz, gx, gy, gz) : mx;
                my = spring ? reff * cross(1, nx, ny, nz, gx, gy, gz) : my;
                mz = spring ? reff * cross(2, nx, ny, nz, gx, gy, gz) : mz;
                // (Into a lane of its own: a select stored back into m_r stopped GCC 12 from
                // vectorising the loop.)
                m_rOut[0][k] = spring ? rx : r0x;
                m_rOut[1][k] = spring ? ry : r0y;
                m_rOut[2][k] = spring ? rz : r0z;
            }
        }
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
