#include "particles/generators/EntrySource.hpp"

#include "core/Error.hpp"
#include "core/random/CounterRng.hpp"
#include "particles/generators/ParticleSpecValidation.hpp"
#include "particles/storage/Uid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace regolith::particles {

namespace {

/// The velocity of the lattice grain `uid`: fixed, or each component uniform in [lo, hi)
/// drawn in the order x, y, z from CounterRng(seed, uid).
core::Vec3 latticeVelocity(VelocitySpec const& velocity, std::uint64_t uid) {
    if (auto const* fixed = std::get_if<core::Vec3>(&velocity))
        return *fixed;
    auto const& r = std::get<RandomVelocity>(velocity);
    if (!(r.lo < r.hi))
        return core::Vec3::Constant(r.lo);
    core::random::CounterRng rng(r.seed, uid);
    double const x = rng.uniform(r.lo, r.hi);
    double const y = rng.uniform(r.lo, r.hi);
    double const z = rng.uniform(r.lo, r.hi);
    return {x, y, z};
}

/// What every grain of an entry takes from it: material type, spin, whether it is fixed.
void applyEntryKeys(ParticleSpec const& spec, std::uint32_t entry, GrainInit& g) {
    g.type = spec.type;
    g.entry = entry;
    g.fixed = spec.fixed;
    if (spec.angularVelocity)
        g.angularVelocity = *spec.angularVelocity;
}

} // namespace

EntrySource::EntrySource(ParticleSpec const& spec, std::size_t index, GeneratorDomain const& domain)
    : m_spec(&spec)
    , m_entry(static_cast<std::uint32_t>(index))
    , m_key(entryKey(index)) {
    if (auto const* lattice = std::get_if<LatticeSpec>(&spec.kind)) {
        m_lattice.emplace(*lattice, domain, m_key);
        m_capacity = m_lattice->capacity();
        m_maxRadius = lattice->radius;
    } else if (auto const* list = std::get_if<ListSpec>(&spec.kind)) {
        m_capacity = list->position.size();
        if (!list->position.empty())
            m_maxRadius = *std::max_element(list->radius.begin(), list->radius.end());
    } else if (auto const* file = std::get_if<FileSpec>(&spec.kind)) {
        prepareFile(*file, domain);
    } else {
        auto const& agglomerate = std::get<AgglomerateSpec>(spec.kind);
        m_capacity = static_cast<std::uint64_t>(agglomerate.count);
        m_maxRadius = agglomerate.count > 0 ? agglomerate.grainRadiusMax : 0.0;
    }
}

bool EntrySource::isAgglomerate() const {
    return std::holds_alternative<AgglomerateSpec>(m_spec->kind);
}

void EntrySource::prepareFile(FileSpec const& file, GeneratorDomain const& domain) {
    m_table = readGrainCsv(file.path, m_key + ".path", file.resolvedFrom);
    auto where = [&](CsvGrain const& g) {
        return fmt::format("{}.path: '{}' line {}", m_key, file.path, g.line);
    };
    if (!m_table.hasDensity && !m_table.hasMass && !file.density)
        throw core::InputError(fmt::format("{}.density: '{}' has neither a density nor a mass "
                                           "column, so the entry must give density",
                                           m_key, file.path));
    std::uint64_t const uidLimit = kUidCounterMask; // uids must fit the counter field
    std::vector<std::pair<std::uint64_t, int>> uids;
    if (m_spec->angularVelocity && m_table.hasAngularVelocity)
        throw core::InputError(fmt::format("{}.angular_velocity: '{}' has angular velocity "
                                           "columns (wx, wy, wz); give one or the other",
                                           m_key, file.path));
    for (auto const& g : m_table.grains) {
        checkGrainPlacement(g.position, g.radius, domain, where(g));
        if (m_spec->fixed &&
            (g.velocity != core::Vec3::Zero() || g.angularVelocity != core::Vec3::Zero()))
            throw core::InputError(fmt::format("{} (vx ... wz): a grain of a fixed entry is held "
                                               "in place; its velocity and angular velocity "
                                               "must be 0",
                                               where(g)));
        if (m_table.hasDensity && !(g.density > 0.0))
            throw core::InputError(
                fmt::format("{} (density): must be positive, got {}", where(g), g.density));
        if (m_table.hasMass && !(g.mass > 0.0))
            throw core::InputError(
                fmt::format("{} (mass): must be positive, got {}", where(g), g.mass));
        if (m_table.hasUid) {
            if (g.uid >= uidLimit)
                throw core::InputError(
                    fmt::format("{} (uid): {} is too large (must be below 2^{} - 1)", where(g),
                                g.uid, kUidCounterBits));
            uids.emplace_back(g.uid, g.line);
        }
        m_maxRadius = std::max(m_maxRadius, g.radius);
    }
    if (!m_table.hasUid) {
        m_capacity = m_table.grains.size();
        return;
    }
    std::sort(uids.begin(), uids.end());
    for (std::size_t i = 1; i < uids.size(); ++i)
        if (uids[i].first == uids[i - 1].first)
            throw core::InputError(fmt::format("{}.path: '{}' lines {} and {} (uid): duplicate "
                                               "uid {}",
                                               m_key, file.path, uids[i - 1].second, uids[i].second,
                                               uids[i].first));
    m_capacity = uids.empty() ? 0 : uids.back().first + 1;
}

std::vector<GrainInit> EntrySource::candidatesIn(RegionSet const& region,
                                                 std::uint64_t uidBegin) const {
    std::vector<GrainInit> out;
    if (region.empty())
        return out;
    if (m_lattice)
        latticeCandidates(region, uidBegin, [&](GrainInit const& g) { out.push_back(g); });
    else if (std::holds_alternative<ListSpec>(m_spec->kind))
        listCandidates(region, uidBegin, out);
    else if (std::holds_alternative<FileSpec>(m_spec->kind))
        fileCandidates(region, uidBegin, out);
    else
        throw core::Error("EntrySource::candidatesIn called for an agglomerate");
    return out;
}

void EntrySource::forEachCandidateIn(RegionSet const& region, std::uint64_t uidBegin,
                                     GrainSink const& sink) const {
    if (region.empty())
        return;
    if (m_lattice) {
        latticeCandidates(region, uidBegin, sink);
        return;
    }
    // Lists and files are held whole by the spec or the CSV table anyway.
    for (GrainInit const& g : candidatesIn(region, uidBegin))
        sink(g);
}

GrainInit EntrySource::latticeGrain(std::uint64_t site, core::Vec3 const& centre,
                                    std::uint64_t uidBegin) const {
    auto const& spec = std::get<LatticeSpec>(m_spec->kind);
    GrainInit g;
    g.uid = uidBegin + site;
    g.position = centre;
    g.velocity = latticeVelocity(spec.velocity, g.uid);
    g.radius = spec.radiusRange ? spec.radiusRange->draw(g.uid) : spec.radius;
    g.density = spec.density;
    g.mass = sphereMass(g.radius, spec.density);
    applyEntryKeys(*m_spec, m_entry, g);
    return g;
}

void EntrySource::latticeCandidates(RegionSet const& region, std::uint64_t uidBegin,
                                    GrainSink const& sink) const {
    auto const boxes = region.boxes();
    if (boxes.size() == 1) { // sites come in increasing linear index: uid order already
        m_lattice->forEachSiteIn(boxes[0], [&](std::uint64_t site, core::Vec3 const& centre) {
            sink(latticeGrain(site, centre, uidBegin));
        });
        return;
    }
    // Boxes may overlap and interleave in index order: sort the site indices, not grains.
    std::vector<std::uint64_t> sites;
    for (auto const& box : boxes)
        m_lattice->forEachSiteIn(
            box, [&](std::uint64_t site, core::Vec3 const&) { sites.push_back(site); });
    std::sort(sites.begin(), sites.end());
    sites.erase(std::unique(sites.begin(), sites.end()), sites.end());
    auto const n = m_lattice->extents();
    for (std::uint64_t const site : sites) {
        auto const s = static_cast<std::int64_t>(site);
        std::int64_t const i = s % n[0], j = (s / n[0]) % n[1], k = s / n[0] / n[1];
        sink(latticeGrain(site, m_lattice->centre(i, j, k), uidBegin));
    }
}

void EntrySource::listCandidates(RegionSet const& region, std::uint64_t uidBegin,
                                 std::vector<GrainInit>& out) const {
    auto const& spec = std::get<ListSpec>(m_spec->kind);
    for (std::size_t i = 0; i < spec.position.size(); ++i) {
        if (!region.containsClosed(spec.position[i]))
            continue;
        GrainInit g;
        g.uid = uidBegin + i;
        g.position = spec.position[i];
        if (spec.radiusRange)
            g.radius = spec.radiusRange->draw(g.uid);
        else
            g.radius = spec.radius.size() == 1 ? spec.radius[0] : spec.radius[i];
        if (!spec.velocity.empty())
            g.velocity = spec.velocity.size() == 1 ? spec.velocity[0] : spec.velocity[i];
        g.density = spec.density;
        g.mass = sphereMass(g.radius, spec.density);
        applyEntryKeys(*m_spec, m_entry, g);
        out.push_back(g);
    }
}

void EntrySource::fileCandidates(RegionSet const& region, std::uint64_t uidBegin,
                                 std::vector<GrainInit>& out) const {
    auto const& spec = std::get<FileSpec>(m_spec->kind);
    for (std::size_t row = 0; row < m_table.grains.size(); ++row) {
        CsvGrain const& c = m_table.grains[row];
        if (!region.containsClosed(c.position))
            continue;
        GrainInit g;
        g.uid = uidBegin + (m_table.hasUid ? c.uid : row);
        g.position = c.position;
        g.velocity = c.velocity;
        g.angularVelocity = c.angularVelocity;
        g.radius = c.radius;
        if (m_table.hasMass) {
            g.mass = c.mass; // kept bit-exact, so a dump read back restores the same masses
            g.density = c.mass / sphereMass(c.radius, 1.0);
        } else {
            g.density = m_table.hasDensity ? c.density : *spec.density;
            g.mass = sphereMass(c.radius, g.density);
        }
        applyEntryKeys(*m_spec, m_entry, g);
        if (m_table.hasType)
            g.type = c.type;
        out.push_back(g);
    }
    if (m_table.hasUid)
        std::sort(out.begin(), out.end(),
                  [](GrainInit const& a, GrainInit const& b) { return a.uid < b.uid; });
}

} // namespace regolith::particles
