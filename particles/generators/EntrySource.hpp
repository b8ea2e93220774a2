#pragma once
/// One `[[particles]]` entry made ready for generation: its uid range width, its largest
/// grain radius, and its candidate grains in a region (before the skipping of grains that
/// overlap earlier entries). Used by generateGrains; agglomerates are packed there instead.
#include "particles/generators/GeneratorDomain.hpp"
#include "particles/generators/GeneratorSpec.hpp"
#include "particles/generators/GrainCsv.hpp"
#include "particles/generators/GrainInit.hpp"
#include "particles/generators/LatticeSites.hpp"
#include "particles/generators/RegionSet.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace regolith::particles {

class EntrySource {
public:
    /// Prepares entry `index` (validated by validateParticleSpecs): lays out the lattice,
    /// or reads and checks the CSV file (throws core::InputError naming the file, line and
    /// column for a grain outside the domain, a non-positive radius, density or mass, a
    /// missing density, or a duplicate uid). Not collective.
    EntrySource(ParticleSpec const& spec, std::size_t index, GeneratorDomain const& domain);

    /// Width of the entry's uid range.
    [[nodiscard]] std::uint64_t capacity() const { return m_capacity; }
    /// Largest radius of the entry's grains (0 if it has none).
    [[nodiscard]] double maxRadius() const { return m_maxRadius; }
    [[nodiscard]] std::string const& key() const { return m_key; }
    [[nodiscard]] ParticleSpec const& spec() const { return *m_spec; }
    [[nodiscard]] bool isAgglomerate() const;

    /// The entry's grains whose centre lies in `region` (closed), uids from `uidBegin`,
    /// sorted by uid, each once. Pre: not an agglomerate.
    [[nodiscard]] std::vector<GrainInit> candidatesIn(RegionSet const& region,
                                                      std::uint64_t uidBegin) const;
    /// The same grains, in the same order, passed to `sink` one by one. A lattice (the
    /// large entries) keeps no grain list: one box is walked in uid order, several boxes
    /// through a sorted list of site indices (8 bytes per site). Pre: not an agglomerate.
    void forEachCandidateIn(RegionSet const& region, std::uint64_t uidBegin,
                            GrainSink const& sink) const;

private:
    void prepareFile(FileSpec const& file, GeneratorDomain const& domain);
    void latticeCandidates(RegionSet const& region, std::uint64_t uidBegin,
                           GrainSink const& sink) const;
    [[nodiscard]] GrainInit latticeGrain(std::uint64_t site, core::Vec3 const& centre,
                                         std::uint64_t uidBegin) const;
    void listCandidates(RegionSet const& region, std::uint64_t uidBegin,
                        std::vector<GrainInit>& out) const;
    void fileCandidates(RegionSet const& region, std::uint64_t uidBegin,
                        std::vector<GrainInit>& out) const;

    ParticleSpec const* m_spec;
    std::uint32_t m_entry;
    std::string m_key;
    std::uint64_t m_capacity = 0;
    double m_maxRadius = 0.0;
    std::optional<LatticeSites> m_lattice;
    CsvGrainTable m_table;
};

} // namespace regolith::particles
