#include "apps/spin_up/RubblePileSections.hpp"

#include "core/Error.hpp"
#include "core/config/ValueChecks.hpp"

#include <fmt/format.h>

namespace regolith::apps {

namespace {

/// Above this d omega / dt (in omega_c^2) the pile is kicked rather than spun up.
constexpr double kMaxRate = 0.1;
/// Above this rotation per step [rad] an equatorial grain's orbit is poorly resolved.
constexpr double kMaxTurnPerStep = 0.02;

PileSection parsePile(core::ConfigTable const& t) {
    PileSection s;
    s.file = t.getOrIf<std::string>(
        "file", s.file, [](std::string const& f) { return !f.empty(); }, "a file name");
    s.recordEvery = t.getOrIf<std::int64_t>(
        "record_every", s.recordEvery, [](std::int64_t n) { return n >= 1; },
        "a positive number of steps");
    s.radius = t.getOrIf<double>(
        "radius", s.radius, [](double r) { return r > 1.0 && std::isfinite(r); },
        "a finite number of initial bulk radii above 1");
    s.linkGap = t.getOrIf<double>("link_gap", s.linkGap, core::isNonNegativeFinite,
                                  "a non-negative finite number of mean grain radii");
    s.settleSteps = t.getOrIf<std::int64_t>("settle_steps", s.settleSteps, core::isNonNegative,
                                            "a non-negative number of steps");
    return s;
}

SpinUpSection parseSpinUp(core::ConfigTable const& t) {
    SpinUpSection s{.table = t};
    core::Vec3 const axis = t.getOrIf<core::Vec3>(
        "axis", s.axis, [](core::Vec3 const& a) { return core::isFiniteVec3(a) && a.norm() > 0; },
        "a non-zero vector");
    s.axis = axis.normalized();
    s.rate = t.getOrIf<double>(
        "rate", s.rate, [](double r) { return r > 0.0 && r <= kMaxRate; },
        fmt::format("a spin-up rate in (0, {:g}] omega_c per dynamical time 1 / omega_c (faster, "
                    "the pile is kicked rather than spun up)",
                    kMaxRate));
    s.finalSpin = t.getOrIf<double>("final_spin", s.finalSpin, core::isPositiveFinite,
                                    "a positive finite spin [omega_c]");
    return s;
}

FlybySection parseFlyby(core::ConfigTable const& t) {
    FlybySection s;
    s.mass = t.getIf<double>("mass", core::isPositiveFinite, "a positive finite mass");
    s.periapsis = t.getOrIf<double>("periapsis", s.periapsis, core::isPositiveFinite,
                                    "a positive finite distance [Roche radii]");
    s.eccentricity = t.getOrIf<double>(
        "eccentricity", s.eccentricity, [](double e) { return e > 1.0 && std::isfinite(e); },
        "a finite eccentricity above 1 (a hyperbola)");
    s.startDistance = t.getOrIf<double>(
        "start_distance", s.startDistance, [&](double d) { return d > s.periapsis; },
        fmt::format("a distance [Roche radii] beyond flyby.periapsis = {:g}", s.periapsis));
    return s;
}

} // namespace

RubblePileScene parseRubblePileScene(core::ConfigTable const& root) {
    RubblePileScene scene;
    if (auto const t = root.findTable("pile"))
        scene.pile = parsePile(*t);
    if (auto const t = root.findTable("spin_up"))
        scene.spinUp = parseSpinUp(*t);
    if (auto const t = root.findTable("flyby"))
        scene.flyby = parseFlyby(*t);
    if (!scene.spinUp && !scene.flyby)
        root.fail("spin_up", "the scene has neither [spin_up] nor [flyby]: expected at least one "
                             "(what is done to the pile)");
    return scene;
}

namespace {

/// InputError "<location>: spin_up.<key>: <message>" (no location for a section made in code).
[[noreturn]] void failSpinUpKey(SpinUpSection const& s, std::string_view key,
                                std::string const& message) {
    if (s.table)
        s.table->fail(key, message);
    throw core::InputError(fmt::format("spin_up.{}: {}", key, message));
}

} // namespace

void checkSpinUpRate(SpinUpSection const& s, double omegaC, double dt) {
    if (s.rate > kMaxRate)
        failSpinUpKey(s, "rate",
                      fmt::format("{:g} omega_c per dynamical time 1 / omega_c = {:.4g} is "
                                  "too fast for the pile to follow; expected at most {:g}",
                                  s.rate, 1.0 / omegaC, kMaxRate));
    double const turn = s.finalSpin * omegaC * dt;
    if (turn > kMaxTurnPerStep)
        failSpinUpKey(
            s, "final_spin",
            fmt::format("at {:g} omega_c (omega_c = {:.4g}) the pile turns {:.3g} rad per "
                        "step of time.dt = {:g}, too coarse for its grains' orbits; "
                        "expected at most {:g} rad per step: lower time.dt or the spin",
                        s.finalSpin, omegaC, turn, dt, kMaxTurnPerStep));
}

} // namespace regolith::apps
