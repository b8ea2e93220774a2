#include "particles/generators/ParticleGenerator.hpp"

#include "core/Error.hpp"
#include "core/memory/MemoryBudget.hpp"
#include "particles/generators/AgglomeratePacker.hpp"
#include "particles/generators/EntrySource.hpp"
#include "particles/generators/OverlapIndex.hpp"
#include "particles/generators/ParticleSpecValidation.hpp"
#include "particles/generators/RegionSet.hpp"
#include "particles/storage/Uid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace regolith::particles {

namespace {

/// Boxes whose neighbourhood must be generated, and the last entry whose overlap tests they
/// serve: the requested boxes (all entries) and each agglomerate's bounding box (the entries
/// before it, which it packs around).
struct Source {
    std::vector<core::AABB> boxes;
    std::size_t anchor = 0;
};

/// margin[j] for the entries j <= anchor: how far around the source's boxes entry j must be
/// known so that every keep decision of a later entry inside its own margin is right. A grain
/// of entry k at distance d of the boxes is tested against grains of entry j < k within
/// r_k + r_j, so margin[j] = max over j < k <= anchor of (margin[k] + maxR[k]) + maxR[j],
/// margin[anchor] = 0.
std::vector<double> sourceMargins(std::vector<double> const& maxRadius, std::size_t anchor) {
    std::vector<double> margin(anchor + 1, 0.0);
    double best = maxRadius[anchor];
    for (std::size_t j = anchor; j-- > 0;) {
        margin[j] = best + maxRadius[j];
        best = std::max(best, margin[j] + maxRadius[j]);
    }
    // Grow by a relative hair so no rounding of the folded boxes can drop a needed grain;
    // generating a little more than needed never changes a decision.
    for (std::size_t j = 0; j < anchor; ++j)
        margin[j] *= 1.0 + 1e-9;
    return margin;
}

/// A lattice entry's grains in this rank's boxes, estimated from its site density, must fit
/// in the node's memory at kBytesPerGrain each (a lower bound: a grain's storage columns
/// alone; docs/results.md measures 273-290 B with everything): a region of 10^9 sites per
/// rank is an input error naming the entry, not a machine filling for minutes.
void requireLatticeFits(EntrySource const& entry, LatticeSpec const& lattice,
                        std::span<core::AABB const> boxes) {
    constexpr double kBytesPerGrain = 200.0;
    core::AABB const& region = lattice.region;
    double const volume = region.extent().prod();
    if (!(volume > 0.0))
        return;
    double local = 0.0;
    for (core::AABB const& b : boxes) {
        core::Vec3 const lo = b.min.cwiseMax(region.min), hi = b.max.cwiseMin(region.max);
        if ((hi.array() > lo.array()).all())
            local += (hi - lo).prod();
    }
    double const grains = static_cast<double>(entry.capacity()) * local / volume;
    // The region named too: with a scenario or a domain-filling lattice, its extent comes
    // from other keys than the entry's own.
    core::requireMemory(grains * kBytesPerGrain, entry.key(),
                        fmt::format("a lattice of about {:.3g} grains in [{:g}, {:g}, {:g}] - "
                                    "[{:g}, {:g}, {:g}] on this rank",
                                    grains, region.min.x(), region.min.y(), region.min.z(),
                                    region.max.x(), region.max.y(), region.max.z()));
}

bool inAnyBox(core::Vec3 const& p, std::span<core::AABB const> boxes) {
    return std::any_of(boxes.begin(), boxes.end(),
                       [&](core::AABB const& b) { return b.contains(p); });
}

} // namespace

std::vector<std::uint64_t> generateGrains(std::span<ParticleSpec const> specs,
                                          core::AABB const& domainBox,
                                          std::array<bool, 3> const& periodic,
                                          std::span<core::AABB const> boxes,
                                          GrainSink const& sink) {
    GeneratorDomain const domain{domainBox, periodic};
    validateParticleSpecs(specs, domain);
    if (specs.size() > std::numeric_limits<std::uint32_t>::max())
        throw core::InputError("particles: too many entries");

    std::vector<EntrySource> entries;
    entries.reserve(specs.size());
    std::vector<std::uint64_t> entryUidBegin(1, 0);
    std::uint64_t const uidLimit = kUidCounterMask; // generated uids fit the counter field
    for (std::size_t k = 0; k < specs.size(); ++k) {
        entries.emplace_back(specs[k], k, domain);
        std::uint64_t const begin = entryUidBegin.back();
        if (entries.back().capacity() > uidLimit - begin)
            throw core::InputError(
                fmt::format("{}: the entries up to this one need more than 2^{} - 1 grain uids",
                            entries.back().key(), kUidCounterBits));
        entryUidBegin.push_back(begin + entries.back().capacity());
        if (auto const* lattice = std::get_if<LatticeSpec>(&specs[k].kind))
            requireLatticeFits(entries.back(), *lattice, boxes);
    }
    if (entries.empty())
        return entryUidBegin;

    std::vector<double> maxRadius;
    for (auto const& e : entries)
        maxRadius.push_back(e.maxRadius());
    std::vector<Source> sources;
    sources.push_back({std::vector<core::AABB>(boxes.begin(), boxes.end()), entries.size() - 1});
    for (std::size_t k = 0; k < entries.size(); ++k)
        if (entries[k].isAgglomerate() && k > 0) {
            auto const& a = std::get<AgglomerateSpec>(specs[k].kind);
            sources.push_back(
                {{core::AABB{a.center.array() - a.radius, a.center.array() + a.radius}}, k});
        }
    std::vector<std::vector<double>> margins;
    for (auto const& s : sources)
        margins.push_back(sourceMargins(maxRadius, s.anchor));

    // Kept grains of the entries so far inside their needed regions, for the skip tests.
    OverlapIndex placed(domain);
    for (std::size_t k = 0; k < entries.size(); ++k) {
        EntrySource const& entry = entries[k];
        std::uint64_t const uidBegin = entryUidBegin[k];
        RegionSet needed;
        if (!entry.isAgglomerate())
            for (std::size_t s = 0; s < sources.size(); ++s)
                if (sources[s].anchor >= k)
                    for (auto const& box : sources[s].boxes)
                        needed.add(box, margins[s][k], domain);
        if (k + 1 == entries.size() && !entry.isAgglomerate()) {
            // No later entry tests against this one: stream it, keep nothing.
            entry.forEachCandidateIn(needed, uidBegin, [&](GrainInit const& g) {
                if (inAnyBox(g.position, boxes) && !placed.overlaps(g.position, g.radius))
                    sink(g);
            });
            break;
        }
        std::vector<GrainInit> kept;
        if (entry.isAgglomerate()) {
            kept = packAgglomerate(specs[k], uidBegin, static_cast<std::uint32_t>(k), domain,
                                   placed, entry.key());
        } else {
            kept = entry.candidatesIn(needed, uidBegin);
            std::erase_if(
                kept, [&](GrainInit const& g) { return placed.overlaps(g.position, g.radius); });
        }
        // Grains of one entry never skip each other: index them only after the whole entry.
        if (k + 1 < entries.size())
            for (auto const& g : kept)
                placed.insert(g.position, g.radius);
        for (auto const& g : kept)
            if (inAnyBox(g.position, boxes))
                sink(g);
    }
    return entryUidBegin;
}

GeneratedGrains generateGrains(std::span<ParticleSpec const> specs, core::AABB const& domain,
                               std::array<bool, 3> const& periodic,
                               std::span<core::AABB const> boxes) {
    GeneratedGrains result;
    result.entryUidBegin = generateGrains(specs, domain, periodic, boxes,
                                          [&](GrainInit const& g) { result.grains.push_back(g); });
    return result;
}

GeneratedGrains generateGrains(std::span<ParticleSpec const> specs, core::AABB const& domain,
                               std::array<bool, 3> const& periodic) {
    core::AABB const all[] = {domain};
    return generateGrains(specs, domain, periodic, all);
}

} // namespace regolith::particles
