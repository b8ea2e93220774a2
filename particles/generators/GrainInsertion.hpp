#pragma once
/// Placing one batch of an `[[insert]]` entry without overlap (LAMMPS `fix pour`): a pure
/// function of the entry, the batch, the grains already near the region and the walls, so that
/// every rank places the same grains, bit for bit, whatever the number of ranks.
#include "particles/generators/GrainInit.hpp"
#include "particles/generators/InsertSpec.hpp"
#include "particles/storage/WallList.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace regolith::particles {

/// A grain already in the domain, as the overlap test sees it.
struct PlacedSphere {
    core::Vec3 centre = core::Vec3::Zero();
    double radius = 0.0;
};

/// The uid of grain `n` of insert entry `entry`: counter n in a rank field no rank creates
/// uids in (just below kFirstReservedRank, one per entry), so inserted grains never collide
/// with generated ones.
[[nodiscard]] Uid insertedUid(std::size_t entry, std::uint64_t n);
/// The entry whose uids `uid` belongs to, or -1 for a grain not inserted.
[[nodiscard]] long insertEntryOf(Uid uid);

/// Periodic lengths of the domain for the overlap test (0 on an open axis).
using PeriodicLengths = std::array<double, 3>;

/// Places grains `first`, `first + 1`, ... (up to `wanted` of them) of insert entry `entry`
/// for batch `batch`: each at the first of its `spec.attempts` draws that overlaps none of
/// `near`, none placed before it and no wall of `walls` (signed distance below the radius).
/// Stops at the first grain that does not fit (the rest wait for the next batch), so the
/// grains inserted are always 0 .. n-1. The result depends on the set `near`, not its order.
/// Not collective.
[[nodiscard]] std::vector<GrainInit>
placeBatch(InsertSpec const& spec, std::size_t entry, std::uint64_t batch, std::uint64_t first,
           std::int64_t wanted, std::span<PlacedSphere const> near, WallList const& walls,
           PeriodicLengths const& periodic);

/// The jamming limit of random sequential addition of equal spheres in 3-D, the
/// densest a batch placed at random can get (Torquato, Uche & Stillinger 2006: 0.38278).
inline constexpr double kRandomAdditionLimit = 0.38;

} // namespace regolith::particles
