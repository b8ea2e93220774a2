#pragma once
/// SpringDashpot::operator() in one lane of a loop the compiler vectorises across contacts, for
/// the batch kernels of pair contacts (SpringDashpotBatch) and wall contacts
/// (SpringDashpotWallBatch): the same IEEE operations in the same order as the scalar code
/// (SpringDashpot::operator(), tangentialForce with projectSpring, rollingResistance), its
/// branches as selects between results computed either way. Included only by the lane files,
/// which are compiled with -fno-trapping-math (a division or root whose result a lane then
/// discards may be evaluated) and REGOLITH_LANE_CODEGEN (cmake/RegolithTargets.cmake).
#include "particles/kernels/SpringDashpotParameters.hpp"
#include "particles/storage/TransposedLoads.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace regolith::particles::spring_lanes {

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

/// One contact's kinematics as SpringDashpot::operator() takes them (ContactState): the
/// normal, the penetration, j's velocity and spin relative to i's, the effective mass and
/// radius and 1/I_i + 1/I_j.
struct LaneState {
    double nx, ny, nz, pen, ux, uy, uz, ox, oy, oz, meff, reff, invIsum;
};

/// SpringDashpot::operator() in one lane: the force f on j and the couple m; updates the
/// tangential spring s and, with Rolling::Spring, the rolling spring r (r is the spring read,
/// rOut the one to store; other laws leave both alone).
template <Rolling kRolling>
[[gnu::always_inline]] inline void
springDashpot(LaneState const& q, Parameters const& p, double dt, double& sx, double& sy,
              double& sz, [[maybe_unused]] double rx, [[maybe_unused]] double ry,
              [[maybe_unused]] double rz, [[maybe_unused]] double& rOutX,
              [[maybe_unused]] double& rOutY, [[maybe_unused]] double& rOutZ, double& fx,
              double& fy, double& fz, double& mx, double& my, double& mz) {
    double const nx = q.nx, ny = q.ny, nz = q.nz;
    // SpringDashpot::operator(): normal force.
    double const cn = 2.0 * p.ratio * std::sqrt(p.k * q.meff);
    double const vn = q.ux * nx + q.uy * ny + q.uz * nz;
    double const vtx = q.ux - vn * nx, vty = q.uy - vn * ny, vtz = q.uz - vn * nz;
    double const fn = p.k * q.pen - cn * vn;
    double const ct = p.ctRatio * cn;
    double const limit = p.mu * (fn < 0.0 ? 0.0 : fn); // std::max(fn, 0.0)
    // tangentialForce: projectSpring, grow, trial force, Coulomb limit.
    double tx, ty, tz;
    springSlider(sx, sy, sz, nx, ny, nz, vtx, vty, vtz, p.kt, ct, limit, dt, tx, ty, tz);
    fx = fn * nx + tx;
    fy = fn * ny + ty;
    fz = fn * nz + tz;
    // rollingResistance (+0.0 where it does not roll, as the scalar code adds).
    mx = 0.0;
    my = 0.0;
    mz = 0.0;
    if constexpr (kRolling != Rolling::None) {
        double const ox = q.ox, oy = q.oy, oz = q.oz, reff = q.reff, invIsum = q.invIsum;
        double const muRoll = p.muRoll;
        // rollingTorque (model A).
        double const spin = ox * nx + oy * ny + oz * nz;
        double const qx = ox - spin * nx, qy = oy - spin * ny, qz = oz - spin * nz;
        double const qNorm = std::sqrt(qx * qx + qy * qy + qz * qz);
        double magnitude = muRoll * reff * fn;
        double const stop = qNorm / (dt * invIsum);
        magnitude = invIsum > 0.0 && stop < magnitude ? stop : magnitude; // std::min
        double const rolling = -magnitude / qNorm;                        // used where rolls only
        bool const rolls = muRoll > 0.0 && fn > 0.0 && qNorm != 0.0;
        mx = rolls ? rolling * qx : 0.0;
        my = rolls ? rolling * qy : 0.0;
        mz = rolls ? rolling * qz : 0.0;
        if constexpr (kRolling == Rolling::Spring) {
            // rollingSpringTorque (model C) where the pair has it.
            bool const spring = p.spring != 0.0;
            double const krTrial = p.kr > 0.0 ? p.kr : 2.25 * muRoll * muRoll * p.k;
            double const kr = p.k < krTrial ? p.k : krTrial; // std::min(krTrial, kn)
            double const vrx = reff * cross(0, ox, oy, oz, nx, ny, nz);
            double const vry = reff * cross(1, ox, oy, oz, nx, ny, nz);
            double const vrz = reff * cross(2, ox, oy, oz, nx, ny, nz);
            double const rr = reff * reff * invIsum;
            double const damped = 2.0 * p.etaR * std::sqrt(3.5 * kr / rr);
            double const stopRolling = 1.0 / (rr * dt);
            double const cr = invIsum > 0.0
                                  ? (stopRolling < damped ? stopRolling : damped) // std::min
                                  : 0.0;
            double const limitRolling = muRoll * (fn < 0.0 ? 0.0 : fn); // std::max(fn, 0.0)
            double ux = rx, uy = ry, uz = rz;
            double gx, gy, gz;
            springSlider(ux, uy, uz, nx, ny, nz, vrx, vry, vrz, kr, cr, limitRolling, dt, gx, gy,
                         gz);
            mx = spring ? reff * cross(0, nx, ny, nz, gx, gy, gz) : mx;
            my = spring ? reff * cross(1, nx, ny, nz, gx, gy, gz) : my;
            mz = spring ? reff * cross(2, nx, ny, nz, gx, gy, gz) : mz;
            // (Into a lane of its own: a select stored back into the spring read stopped GCC
            // 12 from vectorising the loop.)
            rOutX = spring ? ux : rx;
            rOutY = spring ? uy : ry;
            rOutZ = spring ? uz : rz;
        }
    }
}

} // namespace regolith::particles::spring_lanes
