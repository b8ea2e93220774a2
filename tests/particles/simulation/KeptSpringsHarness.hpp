#pragma once
// The harness of the kept-spring tests (KeptSpringsTest.cpp, KeptSpringsFacePairsTest.cpp): a
// scene run by DemStep with the springs kept beside the Verlet lists or in the grains'
// histories, and the comparison of the two runs' final states bit for bit.
#include "core/math/Vec3.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace regolith::particles::kept_springs {

using core::Vec3;

inline constexpr double kRadius = 0.505; // spacing 1: every neighbour overlaps by 0.01 at first

/// A live history entry of a master, as gathered.
struct LiveEntry {
    Uid owner = kInvalidUid, partner = kInvalidUid;
    Vec3 spring;
};

struct Outcome {
    std::vector<std::uint64_t> bits; ///< every master's x, v, w in uid order, as bits
    std::vector<LiveEntry> live;     ///< entries stamped by the last pass, by (owner, partner)
    long long keptMost = 0;          ///< most pairs kept in one step, over all ranks
    long long rebuilds = 0;
    long long shifts = 0; ///< lists shifted with the grains' drift instead of rebuilt
    /// DemStep::contactsOfLastPass summed over the masters after the last step, which ended
    /// Open (the springs kept), and after completeStep (written back), over all ranks; and the
    /// masters whose two counts differ.
    long long contactsOpen = 0, contactsComplete = 0, countsDiffer = 0;
    std::string error;
};

struct Scene {
    domain::ForestSpec spec;
    std::vector<ParticleInit> grains;
    bool walls = true; ///< a floor and a ceiling (z = 0 and the domain's top)
    Vec3 gravity = Vec3(0.0, 0.0, -2.0);
    double dt = 0.002;
    double skin = 0.0; ///< the Verlet skin; 0: a quarter of the radius (DemStep's default)
    /// With skin 0: let the skin widen for the scene as DemStep's default does (ContactDetector,
    /// "A skin for the scene"); the scenes below are built for a quarter of the radius.
    bool skinForTheScene = false;
    int steps = 300;
    bool keepContacts = false; ///< DemStepConfig::keepContacts (false: the driver's setting)
    bool sortByUid = false;    ///< DetectorConfig::sortByUid (no fused list path)
    bool listed = true;        ///< false: no Verlet list (every step a linked-cell pass)
};

/// 6 x 6 x 4 grains on an sc lattice of spacing 1 in [0, 6]^2 x [0, 8], periodic in x and y,
/// floor and ceiling, gravity -2 along z, velocities in [-speed, speed] from the uid, radius
/// `r`.
Scene packing(std::array<int, 3> blocks, double speed = 0.3, double r = kRadius);

/// Runs `scene` with `config`, keeping the springs beside the lists (`keep`) or in the
/// histories; COLLECTIVE over `comm`.
Outcome run(core::Comm const& comm, Scene const& scene, SyncConfig config, bool keep);

/// Both runs went through and end with the same bits: every master's x, v, w and every live
/// history entry (there are some).
void expectSameState(Outcome const& x, Outcome const& y, std::size_t grains);
/// expectSameState, and the first run kept springs (its lists rebuilt or shifted), the
/// second none.
void expectSameBits(Outcome const& kept, Outcome const& histories, std::size_t grains);
/// The runs with and without kept springs of `scene` end with the same bits.
void expectSameBits(core::Comm const& comm, Scene const& scene, SyncConfig config);

} // namespace regolith::particles::kept_springs
