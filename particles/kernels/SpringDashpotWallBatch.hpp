#pragma once
/// The spring-dashpot model over a block's sphere-wall contacts, a batch at a time: the wall
/// half of evaluateWallsWith in a branch-free loop the compiler vectorises across contacts, as
/// SpringDashpotBatch does for the pairs. Evaluated one by one, a wall contact cost about twice a
/// pair contact of the batch kernel (the scalar model waits on its roots and divisions and on
/// a branch per sliding contact): the floor under a pack is a few percent of its step.
///
/// Same bits as evaluateWallsWith with SpringDashpot: the lanes do wallState's and
/// SpringDashpot::operator()'s operations in their order (SpringDashpotLanes.hpp; a fixed wall's
/// velocity and spin enter as +0.0, which leaves every value as it is), the springs are touched
/// and written as withSprings does, and the sink and the walls' loads receive the same calls in
/// contact order (tests/particles/SpringDashpotWallBatchTest.cpp).
#include "core/math/Vec3.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/kernels/SpringDashpotParameters.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::particles {

class SpringDashpotWallBatch {
public:
    static constexpr std::size_t kCapacity = 64;
    static_assert(kCapacity % 8 == 0, "evaluate loads the grains eight contacts at a time");

    /// evaluateWallsWith(ps, walls, list, model, dt, stamp, sink): every contact's spring (on
    /// the sphere's history, keyed by the wall's uid) touched with `stamp` and updated, the
    /// sphere's share handed to `sink` (partner the wall's uid) and the opposite added to the
    /// wall's load, contact by contact in order. Not collective.
    template <ContactSink Sink>
    void evaluate(ParticleStorage& ps, WallList& walls, std::vector<WallContact> const& list,
                  SpringDashpot const& model, double dt, std::uint32_t stamp, Sink&& sink) {
        for (std::size_t first = 0; first < list.size(); first += kCapacity) {
            std::size_t const n = std::min(kCapacity, list.size() - first);
            WallContact const* const batch = list.data() + first;
            evaluateBatch(ps, walls, batch, n, model, dt, stamp);
            for (std::size_t k = 0; k < n; ++k) {
                WallContact const& c = batch[k];
                core::Vec3 const f(m_f[0][k], m_f[1][k], m_f[2][k]);
                sink(c.particle, walls[c.wall].uid, f,
                     core::Vec3(m_torque[0][k], m_torque[1][k], m_torque[2][k]));
                walls.addReaction(c.wall, c.point, f,
                                  core::Vec3(m_couple[0][k], m_couple[1][k], m_couple[2][k]));
            }
        }
    }

private:
    using Parameters = spring_lanes::Parameters;
    using Rolling = spring_lanes::Rolling;
    using Lane = std::array<double, kCapacity>;
    using Lane3 = std::array<Lane, 3>;

    /// Touches the springs of contacts c[0..n), n <= kCapacity, fills the lanes, evaluates
    /// them and writes the springs back: then force, torque (about the sphere's centre) and
    /// couple hold each contact's share.
    void evaluateBatch(ParticleStorage& ps, WallList const& walls, WallContact const* c,
                       std::size_t n, SpringDashpot const& model, double dt, std::uint32_t stamp);
    /// The loop over the lanes, with `uniform`'s parameters in every lane or each lane's own.
    template <Rolling kRolling, bool kUniform>
    void evaluateLanes(Parameters uniform, double dt);

    std::size_t m_size = 0;
    std::array<std::uint32_t, kCapacity> m_sphere{}; ///< storage indices
    std::array<HistoryEntry*, kCapacity> m_entry{};
    std::array<HistoryEntry*, kCapacity> m_rollingEntry{};
    // Inputs: the contact's normal, penetration and point, the sphere's centre, velocity and
    // spin (loaded by evaluateBatch), the wall's surface velocity at the point and spin (+0.0
    // for a fixed wall), the springs (the tangential one updated in place, model C's rolling
    // one into m_rOut).
    alignas(64) Lane3 m_normal, m_point, m_x, m_v, m_w, m_wallV, m_wallW, m_s, m_r;
    alignas(64) Lane m_pen, m_meff, m_radius, m_invI; ///< wallState's m, r and 1/I: the sphere's
    /// Each contact's parameters, with several materials.
    spring_lanes::ParameterLanes<kCapacity> m_parameters;
    // Outputs: the force on the sphere, its torque about the centre, the couple.
    alignas(64) Lane3 m_f, m_torque, m_couple, m_rOut;
};

} // namespace regolith::particles
