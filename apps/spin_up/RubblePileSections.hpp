#pragma once
/// The scene sections of the rubble-pile app (docs/guide/rubble-piles.md): [pile] (what is
/// recorded and where the pile ends), [spin_up] (a torque raising the spin) and [flyby] (a
/// point mass passing on a hyperbola). Rates and distances are in units of the pile's own
/// scales, measured when the run starts: the critical spin omega_c = sqrt(4 pi G rho_bulk / 3)
/// and the bulk radius (PileMeasures).
#include "core/config/ConfigTable.hpp"
#include "core/math/Vec3.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace regolith::apps {

struct PileSection {
    std::string file = "rubble_pile.csv"; ///< pile.file, the record (CSV)
    std::int64_t recordEvery = 100;       ///< pile.record_every [steps]
    double radius = 1.5;                  ///< pile.radius [initial bulk radii]: beyond it, shed
    double linkGap = 0.5; ///< pile.link_gap [mean grain radii]: friends-of-friends gap
    /// pile.settle_steps: steps the pile settles under its own gravity before it is measured
    /// and the spin-up or fly-by begins (time 0 of the record).
    std::int64_t settleSteps = 0;
};

struct SpinUpSection {
    core::Vec3 axis = core::Vec3::UnitZ(); ///< spin_up.axis, normalised
    double rate = 0.02;                    ///< spin_up.rate [omega_c^2]: d omega / dt
    double finalSpin = 1.3;                ///< spin_up.final_spin [omega_c]: the torque stops
    /// Where the keys were written, for the checks once the pile is measured (none when the
    /// section was made in code).
    std::optional<core::ConfigTable> table;
};

struct FlybySection {
    double mass = 0.0;          ///< flyby.mass, the passing point mass
    double periapsis = 2.0;     ///< flyby.periapsis [Roche radii]
    double eccentricity = 2.0;  ///< flyby.eccentricity (> 1: a hyperbola)
    double startDistance = 8.0; ///< flyby.start_distance [Roche radii], before and after
};

struct RubblePileScene {
    PileSection pile;
    std::optional<SpinUpSection> spinUp;
    std::optional<FlybySection> flyby;
};

/// The three sections of `root` (each optional; at least one of [spin_up] and [flyby]),
/// their keys marked as known. InputError naming the key for a bad value.
[[nodiscard]] RubblePileScene parseRubblePileScene(core::ConfigTable const& root);

/// Refuses, naming the key, a spin-up the run cannot follow: a rate above 0.1 omega_c per
/// dynamical time 1 / omega_c (the pile is kicked, not spun up quasi-statically), or a final
/// spin at which the grains would turn more than 0.02 rad per step of `dt` (the orbit of an
/// equatorial grain resolved by fewer than ~300 steps). Same message on every rank.
void checkSpinUpRate(SpinUpSection const& s, double omegaC, double dt);

} // namespace regolith::apps
