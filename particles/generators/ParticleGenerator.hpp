#pragma once
/// The initial grains of a scene: the `[[particles]]` entries generated in order, each rank
/// asking only for the grains whose centre lies in its blocks.
///
/// Rules (docs/design.md, "Scene file"):
///  - Uids. Entry k owns the uid range [entryUidBegin[k], entryUidBegin[k+1]), the entries'
///    ranges laid end to end from 0. Its width and the uid of a grain in it are fixed by the
///    entry alone: lattice: the linear index of the site (LatticeSites), width = candidate
///    sites; list: the index in the list; file: the row index among the data lines, or the
///    file's uid column (width = max uid + 1; so a dump read back as the first entry keeps its
///    uids); agglomerate: the index in generation order. Skipped grains leave gaps.
///  - Skipping. A grain of entry k is dropped iff it overlaps (spheresOverlap, periodic images
///    included) a kept grain of an entry before k. Grains of one entry never skip each other:
///    a lattice with spacing < 2 radius keeps all its (overlapping) sites, as the MESA-PD
///    GranularGas set-up with radius 0.6 and spacing 1 needs, and a file keeps the contact
///    overlaps of a dumped state. An agglomerate instead places its grains around the earlier
///    entries' grains (AgglomeratePacker), so its count is exact.
///  - Random numbers come from core::random::CounterRng keyed by (seed, uid).
/// Hence the result does not depend on the number of ranks or on the boxes asked for: the
/// grains returned for a set of boxes are exactly those of the whole-domain generation whose
/// centre lies in one of the boxes, with the same uids and bit-identical values.
///
/// Locality: an entry's grains are generated only in the boxes grown by the reach of the
/// overlap tests of the later entries (the sum of the largest radii along the chain), so a
/// lattice costs O(sites near the boxes); agglomerates are packed whole on every rank (and
/// the entries before them are generated around the agglomerate's sphere); list and file
/// entries are scanned whole (every rank reads the file).
#include "core/math/AABB.hpp"
#include "particles/generators/GeneratorSpec.hpp"
#include "particles/generators/GrainInit.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace regolith::particles {

struct GeneratedGrains {
    /// The kept grains whose centre lies in one of the requested boxes, sorted by uid.
    std::vector<GrainInit> grains;
    /// specs.size() + 1 values: entry k owns the uids [entryUidBegin[k], entryUidBegin[k+1]);
    /// entryUidBegin.back() is the first uid no entry uses.
    std::vector<std::uint64_t> entryUidBegin;
};

/// Generates the entries `specs` in the domain `domain` with periodic axes `periodic` and
/// returns the kept grains whose centre lies in one of `boxes` (half-open, AABB::contains;
/// boxes in domain coordinates, may overlap; a grain is returned once).
///
/// Throws core::InputError (message starting with the scene key, e.g.
/// "particles[2].spacing: must be positive, got 0") for invalid entries (see
/// validateParticleSpecs), an unreadable or invalid CSV file (bad column, bad number: file,
/// line and column named; grain outside the domain; duplicate uid), an agglomerate that
/// cannot be packed, or more than 2^kUidCounterBits uids in total. Every rank throws the
/// same error for the same input. Not collective: each rank calls it on its own.
[[nodiscard]] GeneratedGrains generateGrains(std::span<ParticleSpec const> specs,
                                             core::AABB const& domain,
                                             std::array<bool, 3> const& periodic,
                                             std::span<core::AABB const> boxes);

/// The same grains, in the same order (by uid), passed to `sink` one by one; returns
/// entryUidBegin. The last entry (in the scenes with millions of grains, the lattice that
/// fills the domain) is streamed without a list of its grains, so a caller that stores the
/// grains as they come holds each grain once. Same errors as above; the sink may have been
/// called for some grains before one is thrown. Not collective.
std::vector<std::uint64_t> generateGrains(std::span<ParticleSpec const> specs,
                                          core::AABB const& domain,
                                          std::array<bool, 3> const& periodic,
                                          std::span<core::AABB const> boxes, GrainSink const& sink);

/// All grains of the domain: generateGrains with the one box `domain`.
[[nodiscard]] GeneratedGrains generateGrains(std::span<ParticleSpec const> specs,
                                             core::AABB const& domain,
                                             std::array<bool, 3> const& periodic);

} // namespace regolith::particles
