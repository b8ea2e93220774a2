#pragma once
// The DemStep tests' pieces: grains of radius 0.5 by default, the periodic box they move in, the
// contact model, and every rank's masters gathered at the end of a run.
#include "core/mpi/Buffer.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/simulation/DemStep.hpp"
#include "tests/particles/sync/SyncTestUtil.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace regolith::particles::demsteptest {

using core::Vec3;

inline constexpr double kDt = 0.002;

/// One master at the end of a run, as every rank sees it after gathering.
struct FinalState {
    Uid uid = kInvalidUid;
    Vec3 x, v, w;
};

/// A sphere of density 1 (synctest::grain with the velocity before the radius).
inline ParticleInit grain(Uid uid, Vec3 const& x, Vec3 const& v, double r = 0.5) {
    return synctest::grain(uid, x, r, v);
}

/// Domain [0, 8]^3, periodic in x and y, floor and ceiling walls, gravity -2 along z.
inline domain::ForestSpec boxSpec(std::array<int, 3> blocks) {
    domain::ForestSpec s;
    s.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
    s.rootBlocks = blocks;
    s.periodic = {true, true, false};
    return s;
}

inline AnyContactModel model() {
    LinearContactParams p;
    p.stiffness = 1000.0; // t_c = pi sqrt(m/2 / k) = 0.05 = 25 steps
    p.tangentialStiffness = 2.0 / 7.0 * p.stiffness;
    p.restitution = 0.8;
    p.friction = 0.4;
    return SpringDashpot(MaterialTable<LinearContactParams>(1, p));
}

/// Every rank's masters, sorted by uid, on every rank. COLLECTIVE.
inline std::vector<FinalState> gatherMasters(core::Comm const& comm, LocalParticles const& local) {
    core::SendBuffer b;
    for (BlockParticles const& bp : local.blocks())
        bp.particles.forEachMaster([&](std::size_t i) {
            b << bp.particles.uid(i) << bp.particles.position(i) << bp.particles.velocity(i)
              << bp.particles.angularVelocity(i);
        });
    auto const bytes = b.bytes();
    std::string const mine(reinterpret_cast<char const*>(bytes.data()), bytes.size());
    auto const parts = comm.gatherStrings(mine, 0);
    std::string all;
    for (auto const& part : parts)
        all += part;
    comm.broadcast(all, 0);
    std::vector<std::byte> data(all.size());
    std::transform(all.begin(), all.end(), data.begin(),
                   [](char c) { return static_cast<std::byte>(c); });
    core::RecvBuffer in(std::move(data));
    std::vector<FinalState> out;
    while (!in.exhausted()) {
        FinalState f;
        in >> f.uid >> f.x >> f.v >> f.w;
        out.push_back(f);
    }
    std::sort(out.begin(), out.end(),
              [](FinalState const& p, FinalState const& q) { return p.uid < q.uid; });
    return out;
}

} // namespace regolith::particles::demsteptest
