#pragma once
// The checkpoint tests' sample: a forest, 64 grains whose values use every bit of their fields,
// this rank's share of them, and their checkpoint written to a file per test and rank count.
#include "domain/BlockForest.hpp"
#include "io/checkpoint/CheckpointWriter.hpp"
#include "io/checkpoint/RestoreGrains.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace regolith::checkpointtest {

using core::Vec3;
namespace fs = std::filesystem;

inline domain::ForestSpec spec() {
    domain::ForestSpec s;
    s.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
    s.rootBlocks = {2, 2, 2};
    s.periodic = {true, false, false};
    return s;
}

/// 64 grains on a lattice with values that use every bit of their fields, rank-independent;
/// every third grain has 1-3 history entries.
inline std::vector<io::GrainState> allGrains() {
    std::vector<io::GrainState> out;
    for (int k = 0; k < 64; ++k) {
        io::GrainState g;
        g.uid = static_cast<particles::Uid>(1000 + 7 * k);
        double const f = 1.0 + k / 3.0;
        g.position = Vec3(0.5 + (k % 4) * 2.0, 0.5 + (k / 4 % 4) * 2.0, 0.5 + (k / 16) * 2.0);
        g.velocity = Vec3(0.1 / f, -0.2 * f, 1e-17 * f);
        g.angularVelocity = Vec3(-0.0, 3.0 / f, 1.0 / 7.0);
        g.orientation = core::Quat(Eigen::AngleAxisd(0.1 * k, Vec3(1, 2, 3).normalized()));
        g.force = Vec3(f, -f / 3.0, 1e300);
        g.torque = Vec3(1e-300, -f, 2.0 / 3.0);
        g.radius = 0.4 + 1e-3 * k;
        g.mass = 4.0 * g.radius * g.radius * g.radius;
        g.type = static_cast<std::uint32_t>(k % 3);
        // Fixed on every fifth grain; the synchronisation class (SOS, and SOS spread by its
        // master alone) on others: every flag a master carries must survive a restart.
        particles::Flags flags;
        flags.set(particles::Flag::Fixed, k % 5 == 0);
        flags.set(particles::Flag::Spreads, k % 7 < 2);
        flags.set(particles::Flag::MasterReachesAll, k % 7 == 0);
        g.flags = flags;
        if (k % 3 == 0)
            for (int e = 0; e <= k % 3 + k % 2; ++e)
                g.history.push_back({g.uid + 1 + static_cast<particles::Uid>(e),
                                     Vec3(1e-3 * e, -f * 1e-4, 1.0 / 3.0), 41U});
        out.push_back(g);
    }
    return out;
}

/// This rank's share: the grains its blocks contain.
inline particles::LocalParticles fill(domain::BlockForest const& forest) {
    particles::LocalParticles local(forest);
    for (io::GrainState const& g : allGrains())
        if (forest.localBlockContaining(g.position) != nullptr) {
            local.addMaster(io::toParticleInit(g));
            for (particles::BlockParticles& bp : local.blocks())
                if (auto i = bp.particles.find(g.uid); i != particles::ParticleStorage::kNotFound)
                    io::restoreHistory(g, bp.particles, i);
        }
    return local;
}

/// A file name per test and rank count (ctest may run the 1- and 4-rank tests together).
inline std::string fileName(core::Comm const& comm, std::string const& what) {
    return fmt::format("checkpoint_test_np{}_{}.h5", comm.size(), what);
}

inline io::CheckpointInfo info() {
    io::CheckpointInfo i;
    i.step = 20;
    i.time = 0.2;
    i.dt = 0.01;
    i.domain = spec().domain;
    i.periodic = spec().periodic;
    i.scene = "[domain]\nmin = [0,0,0]\n";
    i.stateChecksum = "0123456789abcdef";
    return i;
}

/// Whether a temporary of `path` ("<path>.tmp...") is in its directory.
inline bool hasTemporary(std::string const& path) {
    fs::path const dir = fs::absolute(path).parent_path();
    std::string const prefix = fs::path(path).filename().string() + ".tmp";
    for (auto const& entry : fs::directory_iterator(dir))
        if (entry.path().filename().string().starts_with(prefix))
            return true;
    return false;
}

/// Writes the checkpoint of `fill` to `path`. COLLECTIVE.
inline void writeSample(core::Comm const& comm, std::string const& path) {
    domain::BlockForest const forest(comm, spec());
    auto const local = fill(forest);
    auto const grains = io::collectMasters(local);
    io::CheckpointInfo i = info();
    std::uint64_t const bytes = io::writeCheckpoint(comm, path, i, grains);
    EXPECT_GT(bytes, 64U * 20U * 8U);
    EXPECT_EQ(i.grainCount, 64U);
    EXPECT_FALSE(hasTemporary(path));
}

} // namespace regolith::checkpointtest
