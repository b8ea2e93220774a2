// The scene's lattice entries checked against the contact section and the domain
// (LatticeChecks.hpp).
#include "apps/regolith/LatticeChecks.hpp"

#include "core/log/Log.hpp"
#include "particles/generators/LatticeSites.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

namespace regolith::apps {

namespace {

/// Warns where a lattice entry fills a periodic axis whose extent is not a multiple of the
/// lattice's period there (particles::latticePeriod): the sites across the face are then
/// closer (the overlap check refuses them once they overlap) or farther apart than inside,
/// so the lattice is not the uniform one asked for (a gas box of 10.5 at spacing 1 would run
/// with a gap of 1.5 across one face).
void warnLatticeOffPeriod(particles::LatticeSpec const& lattice, core::ConfigTable const& entry,
                          domain::ForestSpec const& forest) {
    std::vector<std::string> axes; // one clause per axis off its period
    for (int a = 0; a < 3; ++a) {
        double const lo = forest.domain.min[a], hi = forest.domain.max[a];
        if (!forest.periodic[static_cast<std::size_t>(a)] || lattice.region.min[a] != lo ||
            lattice.region.max[a] != hi)
            continue;
        double const period = particles::latticePeriod(lattice.lattice, lattice.spacing, a);
        if (!(period > 0.0) || !std::isfinite(period))
            return; // a bad spacing, which the lattice's own check refuses
        double const periods = (hi - lo) / period;
        double const whole = std::max(std::round(periods), 1.0);
        if (std::abs(periods - whole) <= 1e-9 * whole)
            continue;
        axes.push_back(fmt::format("along {} every {}, which does not divide the extent {} "
                                   "({:.6g} periods; e.g. {} would)",
                                   "xyz"[a], period, hi - lo, periods, whole * period));
    }
    if (axes.empty())
        return;
    core::log::warn("{}: {}: the lattice repeats {}: the grains across a periodic face are not "
                    "spaced as inside; make the periodic domain's extent a multiple of the "
                    "period",
                    entry.has("spacing") ? entry.location("spacing") : entry.location(),
                    entry.keyPath("spacing"), fmt::join(axes, "; "));
}

} // namespace

void checkLattices(std::span<particles::ParticleSpec const> specs,
                   std::span<core::ConfigTable const> entries, double initialOverlap,
                   domain::ForestSpec const& forest) {
    for (std::size_t i = 0; i < specs.size(); ++i) {
        auto const* lattice = std::get_if<particles::LatticeSpec>(&specs[i].kind);
        if (!lattice)
            continue;
        double const overlap = 2.0 * lattice->radius - lattice->spacing;
        if (overlap > initialOverlap * lattice->radius)
            entries[i].fail("spacing",
                            fmt::format("grains of radius {:g} at spacing {:g} overlap their "
                                        "neighbours by {:g}, more than contact.initial_overlap = "
                                        "{:g} of the radius; expected a spacing of at least {:g}",
                                        lattice->radius, lattice->spacing, overlap, initialOverlap,
                                        (2.0 - initialOverlap) * lattice->radius));
        warnLatticeOffPeriod(*lattice, entries[i], forest);
    }
}

} // namespace regolith::apps
