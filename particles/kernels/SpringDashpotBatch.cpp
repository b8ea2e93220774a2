#include "particles/kernels/SpringDashpotBatch.hpp"

#include "core/Error.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace regolith::particles {

void SpringDashpotBatch::add(PairOverlap const& p, HistoryEntry& entry, std::uint8_t hint) {
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
}

namespace {

using Vector4 = double __attribute__((vector_size(32)));
using Vector8 = double __attribute__((vector_size(64)));

/// The Vec3s at base + 3 idx[0..7] transposed into eight x, y and z lanes: eight loads and
/// eleven shuffles, where a gather per component cost ~2.5x more (docs/results.md, issue 5,
/// "Loads by index and transposed").
[[gnu::always_inline]] inline void loadTransposed(double const* base, std::uint32_t const* idx,
                                                  double* x, double* y, double* z) {
    Vector4 r[8]; // r[k] = (x_k y_k z_k 0), without reading past z_k (the last copy's Vec3
                  // ends its array); no function returns a vector (an ABI without AVX)
    for (int k = 0; k < 8; ++k) {
        double const* p = base + 3 * std::size_t{idx[k]};
#if defined(__AVX512VL__)
        r[k] = std::bit_cast<Vector4>(_mm256_maskz_loadu_pd(0x7, p));
#elif defined(__AVX__)
        r[k] = std::bit_cast<Vector4>(_mm256_maskload_pd(p, _mm256_setr_epi64x(-1, -1, -1, 0)));
#else
        r[k] = Vector4{p[0], p[1], p[2], 0.0};
#endif
    }
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
}

/// a x b, component `c`, in Eigen's order of operations.
inline double cross(int c, double ax, double ay, double az, double bx, double by, double bz) {
    return c == 0 ? ay * bz - az * by : (c == 1 ? az * bx - ax * bz : ax * by - ay * bx);
}
} // namespace

void SpringDashpotBatch::evaluate(ParticleStorage const& ps, SpringDashpot const& model,
                                  double dt) {
    if (model.hasRollingSpring())
        throw core::Error("SpringDashpotBatch: model C's rolling spring is evaluated pair by pair");
    std::size_t const n = m_size;
    auto const& materials = model.materials();
    // One material (most scenes): the parameters are the same in every lane, so the lanes
    // read them as constants; several: gathered per contact from the tables.
    bool const uniform = materials.numTypes() == 1;
    LinearContactParams const& one = materials(0, 0);
    Parameters const uniformParameters{
        one.stiffness, one.tangentialStiffness,    model.dampingRatio(0, 0),
        one.friction,  one.tangentialDampingRatio, one.rollingFriction};
    if (!uniform) {
        for (std::size_t k = 0; k < n; ++k) {
            std::uint32_t const a = ps.type(m_i[k]), b = ps.type(m_j[k]);
            LinearContactParams const& p = materials(a, b);
            m_k[k] = p.stiffness;
            m_kt[k] = p.tangentialStiffness;
            m_ratio[k] = model.dampingRatio(a, b);
            m_mu[k] = p.friction;
            m_ctRatio[k] = p.tangentialDampingRatio;
            m_muRoll[k] = p.rollingFriction;
        }
    }
    // Rolling resistance costs a root and two divisions per lane; a batch without it (most
    // scenes: rolling friction 0) skips them, with the same bits (its torque is then + 0.0).
    bool rolling = uniform && one.rollingFriction > 0.0;
    for (std::size_t k = 0; !uniform && k < n; ++k)
        rolling = rolling || m_muRoll[k] > 0.0;
    // The centres, velocities and spins, eight contacts at a time (the lanes beyond n repeat
    // contact 0's copies: computed, never read).
    for (std::size_t k = n; k % 8 != 0; ++k) {
        m_i[k] = m_i[0];
        m_j[k] = m_j[0];
    }
    double const* const x = ps.positions().data()->data();
    double const* const v = ps.velocities().data()->data();
    double const* const w = ps.angularVelocities().data()->data();
    for (std::size_t b = 0; b < n; b += 8) {
        loadTransposed(x, &m_i[b], &m_xi[0][b], &m_xi[1][b], &m_xi[2][b]);
        loadTransposed(x, &m_j[b], &m_xj[0][b], &m_xj[1][b], &m_xj[2][b]);
        loadTransposed(v, &m_i[b], &m_vi[0][b], &m_vi[1][b], &m_vi[2][b]);
        loadTransposed(v, &m_j[b], &m_vj[0][b], &m_vj[1][b], &m_vj[2][b]);
        loadTransposed(w, &m_i[b], &m_wi[0][b], &m_wi[1][b], &m_wi[2][b]);
        loadTransposed(w, &m_j[b], &m_wj[0][b], &m_wj[1][b], &m_wj[2][b]);
    }
    GrainScalars const g = GrainScalars::of(ps);
    if (uniform) {
        if (rolling)
            evaluateLanes<true, true>(g, uniformParameters, dt);
        else
            evaluateLanes<false, true>(g, uniformParameters, dt);
    } else {
        if (rolling)
            evaluateLanes<true, false>(g, uniformParameters, dt);
        else
            evaluateLanes<false, false>(g, uniformParameters, dt);
    }
}

template <bool kRolling, bool kUniform>
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
        double const before = sx * sx + sy * sy + sz * sz;
        double const along = sx * nx + sy * ny + sz * nz;
        double const px = sx - along * nx, py = sy - along * ny, pz = sz - along * nz;
        double const after = px * px + py * py + pz * pz;
        bool const keepLength = after > 1e-24 * before;
        double const scale = std::sqrt(before / after); // used where keepLength only
        bool const projected = before != 0.0;
        sx = projected ? (keepLength ? px * scale : 0.0) : sx;
        sy = projected ? (keepLength ? py * scale : 0.0) : sy;
        sz = projected ? (keepLength ? pz * scale : 0.0) : sz;
        sx += vtx * dt;
        sy += vty * dt;
        sz += vtz * dt;
        double tx = -kt * sx - ct * vtx, ty = -kt * sy - ct * vty, tz = -kt * sz - ct * vtz;
        double const f2 = tx * tx + ty * ty + tz * tz;
        bool const slides = f2 > limit * limit;
        double const cut = limit / std::sqrt(f2); // used where slides only
        double const cx = tx * cut, cy = ty * cut, cz = tz * cut;
        double const ux2 = -(cx + ct * vtx) / kt, uy2 = -(cy + ct * vty) / kt,
                     uz2 = -(cz + ct * vtz) / kt;
        sx = slides ? ux2 : sx;
        sy = slides ? uy2 : sy;
        sz = slides ? uz2 : sz;
        tx = slides ? cx : tx;
        ty = slides ? cy : ty;
        tz = slides ? cz : tz;
        bool const tangential = kt > 0.0 && limit > 0.0;
        tx = tangential ? tx : 0.0;
        ty = tangential ? ty : 0.0;
        tz = tangential ? tz : 0.0;
        m_s[0][k] = tangential ? sx : 0.0;
        m_s[1][k] = tangential ? sy : 0.0;
        m_s[2][k] = tangential ? sz : 0.0;
        double const fx = fn * nx + tx, fy = fn * ny + ty, fz = fn * nz + tz;
        // rollingTorque (+0.0 where it does not roll, as the scalar code adds).
        double mx = 0.0, my = 0.0, mz = 0.0;
        if constexpr (kRolling) {
            double const muRoll = kUniform ? uniform.muRoll : m_muRoll[k];
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
