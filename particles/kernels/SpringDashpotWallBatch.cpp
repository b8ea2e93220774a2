#include "particles/kernels/SpringDashpotWallBatch.hpp"

#include "particles/kernels/SpringDashpotLanes.hpp"

#include <cmath>

namespace regolith::particles {

using spring_lanes::cross;

void SpringDashpotWallBatch::evaluateBatch(ParticleStorage& ps, WallList const& walls,
                                           WallContact const* c, std::size_t n,
                                           SpringDashpot const& model, double dt,
                                           std::uint32_t stamp) {
    bool const rollingSpring = model.hasRollingSpring();
    // withSprings' touches, contact by contact (the rolling entry first), then the entries
    // found: a touch may insert an entry and move the others of its sphere's history, and
    // every contact of the batch has entries of its own (one per sphere and wall).
    for (std::size_t k = 0; k < n; ++k) {
        ContactHistory& history = ps.history(c[k].particle);
        Uid const wall = walls[c[k].wall].uid;
        std::uint8_t hint = 0;
        if (rollingSpring)
            history.touch(rollingKey(wall), stamp);
        history.touch(wall, stamp, hint);
    }
    // One material (most scenes): its parameters in every lane, as constants.
    bool const uniform = model.materials().numTypes() == 1;
    Parameters const one = spring_lanes::parametersOf(model, 0, 0);
    bool rolling = uniform && one.muRoll > 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        std::size_t const sphere = c[k].particle;
        Wall const& wall = walls[c[k].wall];
        ContactHistory& history = ps.history(sphere);
        m_sphere[k] = static_cast<std::uint32_t>(sphere);
        m_entry[k] = history.find(wall.uid);
        m_rollingEntry[k] = rollingSpring ? history.find(rollingKey(wall.uid)) : nullptr;
        core::Vec3 const& s = m_entry[k]->spring;
        core::Vec3 const r = rollingSpring ? m_rollingEntry[k]->spring : core::Vec3::Zero();
        core::Vec3 const wallV =
            wall.moving ? wall.surfaceVelocity(c[k].point) : core::Vec3::Zero();
        core::Vec3 const wallW = wall.moving ? wall.motion.angularVelocity : core::Vec3::Zero();
        for (int a = 0; a < 3; ++a) {
            auto const u = static_cast<std::size_t>(a);
            m_normal[u][k] = c[k].normal[a];
            m_point[u][k] = c[k].point[a];
            m_wallV[u][k] = wallV[a];
            m_wallW[u][k] = wallW[a];
            m_s[u][k] = s[a];
            m_r[u][k] = r[a];
        }
        m_pen[k] = c[k].penetration;
        // wallState's effective mass and radius and inverse inertia: the sphere's.
        m_meff[k] = 1.0 / ps.invMass(sphere);
        m_radius[k] = ps.radius(sphere);
        m_invI[k] = ps.invInertia(sphere);
        if (!uniform) {
            Parameters const p = spring_lanes::parametersOf(model, wall.type, ps.type(sphere));
            rolling = rolling || p.muRoll > 0.0;
            m_parameters.set(k, p);
        }
    }
    // The spheres' centres, velocities and spins, eight contacts at a time (the lanes beyond n
    // repeat contact 0's sphere: computed, never read).
    m_size = n;
    for (std::size_t k = n; k % 8 != 0; ++k)
        m_sphere[k] = m_sphere[0];
    for (std::size_t b = 0; b < n; b += 8) {
        spring_lanes::loadTransposed(ps.positions().data()->data(), &m_sphere[b], &m_x[0][b],
                                     &m_x[1][b], &m_x[2][b]);
        spring_lanes::loadTransposed(ps.velocities().data()->data(), &m_sphere[b], &m_v[0][b],
                                     &m_v[1][b], &m_v[2][b]);
        spring_lanes::loadTransposed(ps.angularVelocities().data()->data(), &m_sphere[b],
                                     &m_w[0][b], &m_w[1][b], &m_w[2][b]);
    }
    auto const run = [&]<Rolling kLaw>() {
        if (uniform)
            evaluateLanes<kLaw, true>(one, dt);
        else
            evaluateLanes<kLaw, false>(one, dt);
    };
    if (rollingSpring)
        run.template operator()<Rolling::Spring>();
    else if (rolling)
        run.template operator()<Rolling::Constant>();
    else
        run.template operator()<Rolling::None>();
    // The springs back where withSprings leaves them.
    for (std::size_t k = 0; k < n; ++k) {
        m_entry[k]->spring = core::Vec3(m_s[0][k], m_s[1][k], m_s[2][k]);
        if (rollingSpring)
            m_rollingEntry[k]->spring = core::Vec3(m_rOut[0][k], m_rOut[1][k], m_rOut[2][k]);
    }
}

template <SpringDashpotWallBatch::Rolling kRolling, bool kUniform>
void SpringDashpotWallBatch::evaluateLanes(Parameters const uniform, double dt) {
    std::size_t const n = m_size;
    spring_lanes::ParameterLanes<kCapacity> const& lanes = m_parameters;
    // One contact per iteration, branch-free (SpringDashpotBatch::evaluateLanes): the loop GCC
    // vectorises.
    for (std::size_t k = 0; k < n; ++k) {
        // wallState: the lever arm, the sphere's material velocity at the point and its spin,
        // both relative to the wall's.
        double const rx = m_point[0][k] - m_x[0][k], ry = m_point[1][k] - m_x[1][k],
                     rz = m_point[2][k] - m_x[2][k];
        double const wx = m_w[0][k], wy = m_w[1][k], wz = m_w[2][k];
        double const ux = (m_v[0][k] + cross(0, wx, wy, wz, rx, ry, rz)) - m_wallV[0][k];
        double const uy = (m_v[1][k] + cross(1, wx, wy, wz, rx, ry, rz)) - m_wallV[1][k];
        double const uz = (m_v[2][k] + cross(2, wx, wy, wz, rx, ry, rz)) - m_wallV[2][k];
        spring_lanes::LaneState const q{m_normal[0][k],
                                        m_normal[1][k],
                                        m_normal[2][k],
                                        m_pen[k],
                                        ux,
                                        uy,
                                        uz,
                                        wx - m_wallW[0][k],
                                        wy - m_wallW[1][k],
                                        wz - m_wallW[2][k],
                                        m_meff[k],
                                        m_radius[k],
                                        m_invI[k]};
        Parameters const p = kUniform ? uniform : lanes.at(k);
        double sx = m_s[0][k], sy = m_s[1][k], sz = m_s[2][k];
        double fx, fy, fz, mx, my, mz;
        spring_lanes::springDashpot<kRolling>(q, p, dt, sx, sy, sz, m_r[0][k], m_r[1][k], m_r[2][k],
                                              m_rOut[0][k], m_rOut[1][k], m_rOut[2][k], fx, fy, fz,
                                              mx, my, mz);
        m_s[0][k] = sx;
        m_s[1][k] = sy;
        m_s[2][k] = sz;
        // evaluateWallsWith: the torque about the centre, the couple for the wall's load.
        m_f[0][k] = fx;
        m_f[1][k] = fy;
        m_f[2][k] = fz;
        m_torque[0][k] = cross(0, rx, ry, rz, fx, fy, fz) + mx;
        m_torque[1][k] = cross(1, rx, ry, rz, fx, fy, fz) + my;
        m_torque[2][k] = cross(2, rx, ry, rz, fx, fy, fz) + mz;
        m_couple[0][k] = mx;
        m_couple[1][k] = my;
        m_couple[2][k] = mz;
    }
}

} // namespace regolith::particles
