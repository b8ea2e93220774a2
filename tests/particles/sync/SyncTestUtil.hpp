#pragma once
// Helpers of the synchronisation tests: forests, grains, random gases, moving masters, the
// presence oracle ("a block holds a copy iff the ball reaches it") and gathering small lists.
#include "core/math/AABB.hpp"
#include "core/mpi/Comm.hpp"
#include "core/random/CounterRng.hpp"
#include "domain/BlockForest.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/ParticleSync.hpp"
#include "particles/sync/SyncInvariants.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

namespace regolith::particles::synctest {

namespace domain = regolith::domain;
using core::AABB;
using core::Comm;
using core::Vec3;

inline domain::ForestSpec forestSpec(Vec3 const& min, Vec3 const& max, std::array<int, 3> blocks,
                                     std::array<bool, 3> periodic) {
    domain::ForestSpec s;
    s.domain = AABB{min, max};
    s.rootBlocks = blocks;
    s.periodic = periodic;
    return s;
}

inline std::array<bool, 3> allAxes(bool periodic) {
    return {periodic, periodic, periodic};
}

/// A sphere of density 1.
inline ParticleInit grain(Uid uid, Vec3 const& x, double r, Vec3 const& v = Vec3::Zero()) {
    ParticleInit p;
    p.uid = uid;
    p.position = x;
    p.velocity = v;
    p.radius = r;
    p.mass = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    return p;
}

/// Domain extent on periodic axes, 0 elsewhere (CopyImage.hpp's `period`).
inline Vec3 periodOf(domain::BlockForest const& forest) {
    Vec3 p = Vec3::Zero();
    for (int a = 0; a < 3; ++a)
        if (forest.periodic()[static_cast<std::size_t>(a)])
            p[a] = forest.domain().extent()[a];
    return p;
}

inline std::string methodName(SyncMethod m) {
    return std::string(syncMethodName(m));
}

/// `n` grains with uids makeUid(0, 0..n-1), positions uniform in `domain`, radii uniform in
/// [rMin, rMax), velocities uniform in [-vMax, vMax)^3; identical on every rank.
inline std::vector<ParticleInit> randomGas(AABB const& domain, std::size_t n, double rMin,
                                           double rMax, double vMax, std::uint64_t seed) {
    std::vector<ParticleInit> out;
    for (std::size_t k = 0; k < n; ++k) {
        Uid const uid = makeUid(0, k);
        core::random::CounterRng rng(seed, uid);
        Vec3 x, v;
        for (int a = 0; a < 3; ++a)
            x[a] = rng.uniform(domain.min[a], domain.max[a]);
        for (int a = 0; a < 3; ++a)
            v[a] = rng.uniform(-vMax, vMax);
        out.push_back(grain(uid, x, rng.uniform(rMin, rMax), v));
    }
    return out;
}

/// Adds the grains whose centre lies in a local block; returns how many were added globally.
inline std::size_t addAll(LocalParticles& local, Comm const& comm,
                          std::vector<ParticleInit> const& grains) {
    std::uint64_t added = 0;
    for (ParticleInit const& g : grains)
        added += local.addMaster(g) ? 1 : 0;
    return comm.allReduce(added, core::ReduceOp::Sum);
}

/// Global number of masters.
inline std::uint64_t globalMasters(LocalParticles const& local, Comm const& comm) {
    return comm.allReduce(static_cast<std::uint64_t>(local.countMasters()), core::ReduceOp::Sum);
}

/// The local master of `uid`: its block and index, or {nullptr, 0}.
inline std::pair<BlockParticles*, std::size_t> findMaster(LocalParticles& local, Uid uid) {
    for (BlockParticles& bp : local.blocks()) {
        std::size_t const i = bp.particles.find(uid);
        if (i != ParticleStorage::kNotFound && bp.particles.flags(i).isMaster())
            return {&bp, i};
    }
    return {nullptr, 0};
}

/// Moves every local master by velocity * dt (the integrator's drift, without forces);
/// returns the largest distance a master moved, as an integrator does.
inline double drift(LocalParticles& local, double dt) {
    double largest = 0.0;
    for (BlockParticles& bp : local.blocks())
        bp.particles.forEachMaster([&](std::size_t i) {
            Vec3 const before = bp.particles.position(i);
            bp.particles.position(i) += bp.particles.velocity(i) * dt;
            largest = std::max(largest, (bp.particles.position(i) - before).norm());
        });
    return largest;
}

/// One line per violation, for test messages.
inline std::string joined(std::vector<std::string> const& lines) {
    std::string s;
    for (std::string const& l : lines)
        s += "\n  " + l;
    return s;
}

/// The master's canonical position and radius, known on every rank (one all-reduce).
/// `count` is the global number of masters of `uid`.
struct GrainView {
    Vec3 position = Vec3::Zero();
    double radius = 0.0;
    int count = 0;
};
inline GrainView viewGrain(LocalParticles& local, Comm const& comm, Uid uid) {
    std::array<double, 5> v{0, 0, 0, 0, 0};
    auto const [bp, i] = findMaster(local, uid);
    if (bp != nullptr)
        v = {bp->particles.position(i)[0], bp->particles.position(i)[1],
             bp->particles.position(i)[2], bp->particles.radius(i), 1.0};
    comm.allReduceInPlace(std::span<double>(v), core::ReduceOp::Sum);
    return {Vec3(v[0], v[1], v[2]), v[3], static_cast<int>(v[4])};
}

/// The presence oracle: for every local block and image k in {-1, 0, 1} on periodic axes,
/// the block holds copy (uid, k) iff the Euclidean distance from x + k * period to its box is
/// below r (cases within `band` of r are not judged), and nothing else of `uid`; the master
/// iff the box contains x. Returns the number of copies this rank should hold. Local.
inline std::size_t expectPresence(LocalParticles const& local, Uid uid, Vec3 const& x, double r,
                                  std::string const& context, double band = 1e-7) {
    Vec3 const period = periodOf(local.forest());
    std::size_t expected = 0;
    for (BlockParticles const& bp : local.blocks()) {
        ParticleStorage const& ps = bp.particles;
        AABB const& box = bp.block->aabb;
        std::size_t held = 0;
        for (std::size_t i = 0; i < ps.size(); ++i)
            held += ps.uid(i) == uid ? 1 : 0;
        std::size_t judged = 0, needed = 0, present = 0;
        // No image through a wrapped face (wrappedAxes: the cells find those pairs).
        std::array<bool, 3> const wrapped = wrappedAxes(local.forest());
        int const rx = period[0] > 0 && !wrapped[0] ? 1 : 0,
                  ry = period[1] > 0 && !wrapped[1] ? 1 : 0,
                  rz = period[2] > 0 && !wrapped[2] ? 1 : 0;
        for (int i = -rx; i <= rx; ++i)
            for (int j = -ry; j <= ry; ++j)
                for (int l = -rz; l <= rz; ++l) {
                    CopyImage const k{static_cast<std::int8_t>(i), static_cast<std::int8_t>(j),
                                      static_cast<std::int8_t>(l)};
                    double const d = std::sqrt(box.sqDistance(localPosition(x, k, period)));
                    bool const has = ps.contains(uid, k);
                    present += has ? 1 : 0;
                    if (std::abs(d - r) < band)
                        continue;
                    ++judged;
                    needed += d < r ? 1 : 0;
                    EXPECT_EQ(has, d < r)
                        << context << ": block " << bp.block->id.toString() << " image (" << i
                        << "," << j << "," << l << ") at distance " << d << " from the grain "
                        << "at (" << x.transpose() << ") with radius " << r;
                }
        EXPECT_EQ(held, present) << context << ": block " << bp.block->id.toString()
                                 << " holds copies of uid " << uid << " at other images";
        bool const master = box.contains(x);
        std::size_t const m = ps.find(uid);
        EXPECT_EQ(master, m != ParticleStorage::kNotFound && ps.flags(m).isMaster())
            << context << ": block " << bp.block->id.toString() << " and the master at ("
            << x.transpose() << ")";
        expected += needed;
    }
    return expected;
}

/// (block, uid, image, master?) of every copy on this rank, sorted.
using CopySet = std::vector<std::tuple<std::uint64_t, Uid, CopyImage, bool>>;
inline CopySet copySet(LocalParticles const& local) {
    CopySet s;
    for (BlockParticles const& bp : local.blocks())
        for (std::size_t i = 0; i < bp.particles.size(); ++i)
            s.emplace_back(bp.block->id.raw(), bp.particles.uid(i), bp.particles.image(i),
                           bp.particles.flags(i).isMaster());
    std::sort(s.begin(), s.end());
    return s;
}

inline bool sameBits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
inline bool sameBits(Vec3 const& a, Vec3 const& b) {
    return sameBits(a[0], b[0]) && sameBits(a[1], b[1]) && sameBits(a[2], b[2]);
}

/// The union over ranks of one list of uids per rank, on every rank (sorted).
inline std::vector<Uid> gatherUids(Comm const& comm, std::vector<Uid> const& mine) {
    std::string s(mine.size() * sizeof(Uid), '\0');
    if (!mine.empty())
        std::memcpy(s.data(), mine.data(), s.size());
    std::string all;
    for (std::string const& part : comm.gatherStrings(s, 0))
        all += part;
    comm.broadcast(all, 0);
    std::vector<Uid> out(all.size() / sizeof(Uid));
    if (!out.empty())
        std::memcpy(out.data(), all.data(), out.size() * sizeof(Uid));
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace regolith::particles::synctest
