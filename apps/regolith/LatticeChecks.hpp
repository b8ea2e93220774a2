#pragma once
/// The checks of the scene's lattice entries ([[particles]] with kind = "lattice") that need
/// more than the entry: the contact section's initial overlap and the domain's periods.
#include "core/config/ConfigTable.hpp"
#include "domain/ForestSpec.hpp"
#include "particles/generators/GeneratorSpec.hpp"

#include <span>

namespace regolith::apps {

/// For each lattice among `specs` (entry k of `entries` wrote spec k): refuses a spacing whose
/// neighbours overlap by more than `initialOverlap` of the radius (they would be refused after
/// generation, and a spacing far below the diameter generates more grains than memory holds
/// first), and warns once per entry where the lattice fills a periodic axis of `forest` whose
/// extent is not a multiple of its period there. Throws core::InputError naming the entry's
/// `spacing`. Not collective.
void checkLattices(std::span<particles::ParticleSpec const> specs,
                   std::span<core::ConfigTable const> entries, double initialOverlap,
                   domain::ForestSpec const& forest);

} // namespace regolith::apps
