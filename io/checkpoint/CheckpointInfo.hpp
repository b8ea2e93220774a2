#pragma once
/// What a checkpoint file says about itself besides the grains (io/checkpoint/GrainState.hpp):
/// the format version, where the run stood, the scene it was written for, and checksums.
///
/// File layout (HDF5, one file per checkpoint; N grains, H contact-history entries in all):
///   attributes of "/": format_version, step, time, dt, domain_min[3], domain_max[3],
///                      periodic[3], scene (text), state_checksum (text), grain_count,
///                      history_count, gravity_updates, gravity_potential_energy,
///                      gravity_since_update, gravity_interval, checksum
///   datasets: the entries of particles::kGrainQuantities (GrainQuantities.hpp), in its order:
///             uid[N], position[N,3], velocity[N,3], angular_velocity[N,3],
///             orientation[N,4] (w, x, y, z), force[N,3], torque[N,3], radius[N], mass[N],
///             type[N], flags[N], gravity_reference[N,3], gravity_field[N,3],
///             gravity_slope[N,3] (NaN rows: no self-gravity record), history_offset[N] (first
///             entry of the grain), history_count[N], history_partner[H], history_spring[H,3],
///             history_stamp[H], then one dataset per grain field a program declared
///             (particles/storage/GrainFields.hpp), named as declared, [N] or [N,3]
/// `checksum` is the FNV-1a of the attributes plus the sum over grains of grainHash: any
/// slice of grains can be hashed by any rank, so a file is verified on any rank count.
#include "core/math/AABB.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace regolith::io {

/// The checkpoint format this build writes and reads. Bump it with every layout change.
/// 2: self-gravity state (gravity_* attributes and datasets) added.
/// 3: the update interval's state (gravity_since_update, gravity_interval, gravity_slope).
inline constexpr std::int64_t kCheckpointFormatVersion = 3;

struct CheckpointInfo {
    std::int64_t formatVersion = kCheckpointFormatVersion;
    std::int64_t step = 0; ///< time steps done when the checkpoint was written
    double time = 0.0;     ///< simulated time at that step [time]
    double dt = 0.0;       ///< the run's time step [time]
    core::AABB domain;     ///< the forest's domain the run used
    std::array<bool, 3> periodic{false, false, false};
    std::string scene;              ///< the scene as text (provenance; not parsed on restart)
    std::string stateChecksum;      ///< the run's state checksum of these masters (apps), or ""
    std::uint64_t grainCount = 0;   ///< over all ranks (filled by the writer)
    std::uint64_t historyCount = 0; ///< over all ranks (filled by the writer)
    /// Self-gravity: field updates so far (0: none, or no self-gravity) and ½ Σ m φ of the
    /// last one [energy]; the per-grain records are GrainState::gravity*.
    std::int64_t gravityUpdates = 0;
    double gravityPotentialEnergy = 0.0;
    /// gravity.update_every: steps since the last update, and the interval then (0: none).
    std::int64_t gravitySinceUpdate = 0;
    std::int64_t gravityInterval = 0;
};

/// FNV-1a of every field of `info` (the header part of the file checksum). Not collective.
[[nodiscard]] std::uint64_t infoHash(CheckpointInfo const& info);

} // namespace regolith::io
