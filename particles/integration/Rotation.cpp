#include "particles/integration/Rotation.hpp"

#include <array>
#include <cmath>
#include <cstddef>

namespace regolith::particles {

namespace {

/// The rotation quaternion (c, s w) of the rotation vector w dt, for the small angles of a
/// DEM step (a^2 = |w|^2 dt^2 < 1e-4): the Taylor series of cos(a/2) and sin(a/2)/|w| to the
/// a^6 term are exact to round-off (the next terms are below a^8/1e7 < 1e-23) and need no sqrt,
/// sin or cos. Horner form with the reciprocals of 8, 384, 46080 (cos) and 48, 3840, 645120
/// (sin): multiplications, not divisions.
constexpr double kSmallAngle2 = 1e-4;
double smallAngleCos(double a2) {
    return 1.0 + a2 * (-1.0 / 8.0 + a2 * (1.0 / 384.0 - a2 * (1.0 / 46080.0)));
}
double smallAngleSinOverW(double a2, double dt) {
    return dt * (0.5 + a2 * (-1.0 / 48.0 + a2 * (1.0 / 3840.0 - a2 * (1.0 / 645120.0))));
}

/// r q (Hamilton product), spelled out so that the batched loop and rotate() do the same
/// operations in the same order. (This file is built without basic-block SLP: GCC 12 would
/// otherwise fuse rotate()'s product into vfmsubadd despite -ffp-contract=off.)
struct Q {
    double w, x, y, z;
};
Q product(Q const& r, Q const& q) {
    return {r.w * q.w - r.x * q.x - r.y * q.y - r.z * q.z,
            r.w * q.x + r.x * q.w + r.y * q.z - r.z * q.y,
            r.w * q.y - r.x * q.z + r.y * q.w + r.z * q.x,
            r.w * q.z + r.x * q.y - r.y * q.x + r.z * q.w};
}
double squaredNorm(Q const& q) {
    return q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
}
/// r is a unit quaternion to round-off, so |q| drifts by a few ulps per step at most: the
/// square root and division of a normalisation are needed only now and then.
bool needsNormalising(double n2) {
    return std::abs(n2 - 1.0) > 1e-14;
}
void store(core::Quat& to, Q const& q) {
    to.w() = q.w;
    to.x() = q.x;
    to.y() = q.y;
    to.z() = q.z;
}

/// Grains per batch: enough for the vectorised loop to dominate its set-up, few enough for
/// the lanes (8 KiB) to stay in L1.
constexpr std::size_t kLanes = 64;

/// One batch in structure-of-arrays lanes: the angular velocity and orientation gathered from
/// the storage, the new orientation, and whether the lane's result can be stored as is.
struct Lanes {
    std::array<std::size_t, kLanes> index;
    std::array<double, kLanes> wx, wy, wz, qw, qx, qy, qz;
    std::array<double, kLanes> ow, ox, oy, oz;
    std::array<bool, kLanes> done;
};

/// The small-angle path of rotate() for every lane, branch-free so that it vectorises. A lane
/// is `done` if that path is rotate()'s (small, non-zero angle) and no normalisation follows.
void evaluate(Lanes& b, std::size_t n, double dt) {
    for (std::size_t l = 0; l < n; ++l) {
        double const wx = b.wx[l], wy = b.wy[l], wz = b.wz[l];
        double const w2 = wx * wx + wy * wy + wz * wz;
        double const a2 = w2 * dt * dt;
        double const c = smallAngleCos(a2);
        double const s = smallAngleSinOverW(a2, dt);
        Q const out = product({c, s * wx, s * wy, s * wz}, {b.qw[l], b.qx[l], b.qy[l], b.qz[l]});
        b.ow[l] = out.w;
        b.ox[l] = out.x;
        b.oy[l] = out.y;
        b.oz[l] = out.z;
        b.done[l] = (w2 != 0.0) & (a2 < kSmallAngle2) & !needsNormalising(squaredNorm(out));
    }
}

void flush(ParticleStorage& ps, Lanes& b, std::size_t n, double dt) {
    evaluate(b, n, dt);
    for (std::size_t l = 0; l < n; ++l) {
        core::Quat q = ps.orientation(b.index[l]);
        if (b.done[l])
            store(q, {b.ow[l], b.ox[l], b.oy[l], b.oz[l]});
        else // zero or large angle, or a normalisation: the scalar path decides
            rotate(q, ps.angularVelocity(b.index[l]), dt);
        ps.setOrientation(b.index[l], q);
    }
}

} // namespace

void rotate(core::Quat& q, core::Vec3 const& angularVelocity, double dt) {
    double const wx = angularVelocity.x(), wy = angularVelocity.y(), wz = angularVelocity.z();
    double const w2 = wx * wx + wy * wy + wz * wz;
    if (w2 == 0.0)
        return;
    double const a2 = w2 * dt * dt;
    double c = 0.0;
    double s = 0.0; // sin(a/2) / |w|
    if (a2 < kSmallAngle2) [[likely]] {
        c = smallAngleCos(a2);
        s = smallAngleSinOverW(a2, dt);
    } else {
        double const w = std::sqrt(w2);
        c = std::cos(0.5 * w * dt);
        s = std::sin(0.5 * w * dt) / w;
    }
    Q const out = product({c, s * wx, s * wy, s * wz}, {q.w(), q.x(), q.y(), q.z()});
    store(q, out);
    double const n2 = squaredNorm(out);
    if (needsNormalising(n2)) {
        double const inv = 1.0 / std::sqrt(n2);
        store(q, {out.w * inv, out.x * inv, out.y * inv, out.z * inv});
    }
}

void rotateMoving(ParticleStorage& ps, double dt) {
    Lanes b;
    std::size_t n = 0;
    for (std::size_t i = 0, size = ps.size(); i < size; ++i) {
        Flags const f = ps.flags(i);
        if (f.isShadow() || f.isFixed())
            continue;
        core::Vec3 const& w = ps.angularVelocity(i);
        core::Quat const& q = ps.orientation(i);
        b.index[n] = i;
        b.wx[n] = w.x();
        b.wy[n] = w.y();
        b.wz[n] = w.z();
        b.qw[n] = q.w();
        b.qx[n] = q.x();
        b.qy[n] = q.y();
        b.qz[n] = q.z();
        if (++n == kLanes) {
            flush(ps, b, n, dt);
            n = 0;
        }
    }
    flush(ps, b, n, dt);
}

} // namespace regolith::particles
