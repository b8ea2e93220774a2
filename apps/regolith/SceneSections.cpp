#include "apps/regolith/SceneSections.hpp"

#include "apps/regolith/InsertSection.hpp"
#include "apps/regolith/LatticeChecks.hpp"
#include "apps/regolith/SceneKeyLocation.hpp"
#include "apps/regolith/WallSection.hpp"
#include "core/Error.hpp"
#include "core/config/ValueChecks.hpp"
#include "core/log/Log.hpp"
#include "coupling/gravity/GravityMethod.hpp"
#include "domain/ForestConfig.hpp"
#include "domain/SpecValidation.hpp"
#include "particles/generators/ParticleSpecValidation.hpp"
#include "particles/simulation/ContactModelRegistry.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace regolith::apps {

using core::isFiniteVec3;
using core::isNonNegative;
using core::isNonNegativeFinite;
using core::isPositiveFinite;

namespace {

using namespace std::string_view_literals;

/// In the order of particles::SyncMethod (NextNeighbour, ShadowOwner, Hybrid); the names are
/// particles::syncMethodName's.
constexpr std::array kSyncNames{"nns"sv, "sos"sv, "hybrid"sv};
/// In the order of domain::Subdomains (Blocks, RankBoxes).
constexpr std::array kSubdomainNames{"blocks"sv, "merged"sv};
constexpr std::array kRollingNames{"constant"sv, "spring"sv};
constexpr std::array kIntegratorNames{"euler"sv, "verlet"sv};

/// gravity.check_every and update_every above this are typos: a run has far fewer updates.
constexpr std::int64_t kMaxEvery = 1000000;

/// Whether `key` (present) is the word `word`; else its integer in [lo, hi] goes to `value`.
/// InputError naming the key, with `expected`, for anything else.
bool isWordElseInteger(core::ConfigTable const& t, char const* key, std::string_view word,
                       std::int64_t lo, std::int64_t hi, char const* expected,
                       std::int64_t& value) {
    if (t.kindOf(key) == core::ConfigKind::String && t.getString(key) == word)
        return true;
    if (t.kindOf(key) != core::ConfigKind::Integer)
        t.failExpected(key, expected);
    value = t.getIf<std::int64_t>(
        key, [&](std::int64_t n) { return n >= lo && n <= hi; }, expected);
    return false;
}

/// The parsed section if present, else its defaults (every key of these sections is optional).
template <class Section, class Parse>
Section optionalSection(core::ConfigTable const& root, std::string_view key, Parse parse) {
    auto const t = root.findTable(key);
    return t ? parse(*t) : Section{};
}

} // namespace

TimeSection parseTime(core::ConfigTable const& t) {
    TimeSection s;
    if (t.kindOf("dt") == core::ConfigKind::String) {
        if (t.getString("dt") != "auto")
            t.failExpected("dt", "a positive finite number or \"auto\"");
        s.dtAuto = true;
    } else {
        s.dt = t.getIf<double>("dt", isPositiveFinite, "a positive finite number or \"auto\"");
    }
    s.steps = t.getIf<std::int64_t>("steps", isNonNegative, "a non-negative integer");
    s.allowUnstable = t.getOr<bool>("allow_unstable", false);
    s.integrator = static_cast<Integrator>(t.getChoiceOr(
        "integrator", kIntegratorNames, static_cast<std::size_t>(Integrator::Verlet)));
    if (t.has("orientation")) {
        core::ConfigKind const kind = t.kindOf("orientation");
        bool const isAuto =
            kind == core::ConfigKind::String && t.getString("orientation") == "auto";
        if (!isAuto && kind != core::ConfigKind::Boolean)
            t.failExpected("orientation", "true, false or \"auto\"");
        if (!isAuto) {
            s.orientation = t.getBool("orientation");
            s.orientationAuto = false;
        }
    }
    if (!s.orientation && s.integrator != Integrator::Verlet)
        t.failExpected("orientation", "true with integrator = \"euler\" (only velocity Verlet "
                                      "can leave orientations out)");
    return s;
}

SyncSection parseSync(core::ConfigTable const& t) {
    SyncSection s;
    s.method = static_cast<particles::SyncMethod>(t.getChoiceOr(
        "method", kSyncNames, static_cast<std::size_t>(particles::SyncMethod::Hybrid)));
    s.reproducible = t.getOr<bool>("reproducible", false);
    if (t.has("skin")) {
        core::ConfigKind const kind = t.kindOf("skin");
        bool const isAuto = kind == core::ConfigKind::String && t.getString("skin") == "auto";
        bool const isNumber = kind == core::ConfigKind::Float || kind == core::ConfigKind::Integer;
        if (!isAuto && !isNumber)
            t.failExpected("skin", "a non-negative finite length or \"auto\"");
        if (!isAuto) {
            s.skin = t.getIf<double>("skin", isNonNegativeFinite,
                                     "a non-negative finite length or \"auto\"");
            s.skinAuto = false;
        }
    }
    s.subdomains = static_cast<domain::Subdomains>(t.getChoiceOr(
        "subdomains", kSubdomainNames, static_cast<std::size_t>(domain::Subdomains::RankBoxes)));
    if (s.skin > 0.0 && s.method == particles::SyncMethod::ShadowOwner)
        t.failExpected("skin", "0 with method = \"sos\" (the skin applies to NNS-class grains)");
    return s;
}

BalanceSection parseBalance(core::ConfigTable const& t) {
    BalanceSection s;
    if (t.has("every"))
        s.everyAuto =
            isWordElseInteger(t, "every", "auto", 0, std::numeric_limits<std::int64_t>::max(),
                              "a number of steps >= 0 or \"auto\"", s.every);
    s.threshold = t.getOrIf<double>(
        "threshold", s.threshold, [](double x) { return x >= 1.0 && std::isfinite(x); },
        "a finite imbalance (max / mean load) >= 1");
    if (t.has("split_levels"))
        s.splitAuto = isWordElseInteger(t, "split_levels", "auto", 0, domain::kMaxRefineLevel,
                                        "a number of levels in [0, 8] or \"auto\"", s.splitLevels);
    return s;
}

ContactSection parseContact(core::ConfigTable const& t) {
    ContactSection s;
    particles::ContactModelEntry const& entry = particles::contactModelEntry(t);
    s.model = entry.name;
    s.elasticity = entry.elasticity;
    if (entry.checkKeys)
        entry.checkKeys(t);
    s.table = t;
    s.rollingSpring.enabled = t.getChoiceOr("rolling_model", kRollingNames, 0) == 1;
    for (char const* key : {"rolling_stiffness", "rolling_damping_ratio"})
        if (t.has(key) && !s.rollingSpring.enabled)
            t.fail(key, "applies only with rolling_model = \"spring\" (model C)");
    s.rollingSpring.stiffness =
        t.getOrIf<double>("rolling_stiffness", s.rollingSpring.stiffness, isNonNegativeFinite,
                          "a non-negative finite number (0: 2.25 rolling_friction^2 stiffness)");
    s.rollingSpring.dampingRatio =
        t.getOrIf<double>("rolling_damping_ratio", s.rollingSpring.dampingRatio,
                          isNonNegativeFinite, "a non-negative finite number");
    s.initialOverlap = t.getOrIf<double>(
        "initial_overlap", s.initialOverlap, [](double f) { return f >= 0.0 && f < 1.0; },
        "a fraction of the smaller radius in [0, 1)");
    if (t.has("neighbour_skin"))
        s.neighbourSkin = t.getOrIf<double>("neighbour_skin", 0.0, isNonNegativeFinite,
                                            "a non-negative finite length (0: no neighbour list)");
    return s;
}

namespace {

/// Whether `key` of [gravity] may stand although the method ignores it: the file gave it (for
/// the file's own method) and a --set of gravity.self supersedes that method. A --set of the
/// key itself, or a file giving both, is a request that would go unheard.
bool supersededBySetMethod(core::ConfigTable const& t, std::string_view key) {
    return !t.location(key).starts_with("--set") && t.location("self").starts_with("--set");
}

/// gravity.self's words: "none", the registered methods, "auto".
std::vector<std::string_view> selfNames(std::vector<std::string> const& methods) {
    std::vector<std::string_view> names{"none"};
    names.insert(names.end(), methods.begin(), methods.end());
    names.push_back("auto");
    return names;
}

/// The registered methods with `property`, quoted, the last after `conjunction`: "\"pm\" or
/// \"p3m\"".
std::string methodsWith(bool coupling::GravityMethodEntry::*property,
                        std::string_view conjunction) {
    std::vector<std::string> names;
    for (std::string const& name : coupling::gravityMethodNames())
        if (coupling::gravityMethod(name).*property)
            names.push_back(fmt::format("\"{}\"", name));
    std::string out;
    for (std::size_t k = 0; k < names.size(); ++k)
        out += fmt::format("{}{}",
                           k == 0                  ? ""
                           : k + 1 == names.size() ? conjunction
                                                   : ", ",
                           names[k]);
    return out;
}

} // namespace

GravitySection parseGravity(core::ConfigTable const& t) {
    GravitySection s;
    s.external =
        t.getOrIf<core::Vec3>("external", s.external, isFiniteVec3, "an array of 3 finite numbers");
    std::vector<std::string> const methods = coupling::gravityMethodNames();
    std::vector<std::string_view> const choices = selfNames(methods);
    s.self = std::string(choices[t.getChoiceOr("self", choices, 0)]);
    coupling::GravityMethodEntry const* method = coupling::findGravityMethod(s.self);
    if (method && method->readKeys)
        s.methodOptions = method->readKeys(t);
    s.G = t.getOrIf<double>("G", s.G, isPositiveFinite, "a positive finite number");
    s.theta = t.getOrIf<double>("theta", s.theta, isPositiveFinite, "a positive finite number");
    // With "auto", a theta would be replaced without a word.
    if (s.self == "auto" && t.has("theta") && !supersededBySetMethod(t, "theta"))
        t.fail("theta", "is chosen by gravity.self = \"auto\" (the largest opening angle that "
                        "meets gravity.accuracy); set gravity.self = \"tree\" to use this one, "
                        "or leave it out");
    if (t.has("update_threshold") && t.kindOf("update_threshold") == core::ConfigKind::String) {
        if (t.getString("update_threshold") != "auto")
            t.failExpected("update_threshold", "a non-negative finite number or \"auto\"");
        s.thresholdAuto = true;
    } else {
        s.updateThreshold =
            t.getOrIf<double>("update_threshold", s.updateThreshold, isNonNegativeFinite,
                              "a non-negative finite number or \"auto\"");
    }
    s.accuracyGiven = t.has("accuracy");
    s.accuracy = t.getOrIf<double>(
        "accuracy", s.accuracy, [](double a) { return a > 0.0 && a < 1.0; },
        "a relative force error in (0, 1)");
    if (t.has("update_every"))
        s.updateEveryAdaptive =
            isWordElseInteger(t, "update_every", "adaptive", 1, kMaxEvery,
                              "a number of steps in [1, 1000000] or \"adaptive\"", s.updateEvery);
    if (t.has("check_every"))
        s.checkEveryAuto = isWordElseInteger(
            t, "check_every", "auto", 0, kMaxEvery,
            "a number of updates in [0, 1000000] (0: never) or \"auto\"", s.checkEvery);
    s.softening = t.getOrIf<double>("softening", s.softening, isNonNegativeFinite,
                                    "a non-negative finite number");
    // A method without a Plummer length (pm's mesh, the node methods' node-to-node sums) with
    // a softening is refused, or the softening dropped with a warning where a --set of the
    // method supersedes the file's (the measured-accuracy check must not compare with a
    // softened sum either).
    if (s.softening > 0.0 && method && !method->softens) {
        if (!supersededBySetMethod(t, "softening"))
            t.fail("softening",
                   fmt::format("gravity.self = \"{}\" does not soften: a Plummer length "
                               "applies to {}; use one of those, or 0",
                               s.self,
                               methodsWith(&coupling::GravityMethodEntry::softens, " and ")));
        core::log::warn("{}: gravity.softening = {:g} does not apply to gravity.self = \"{}\" "
                        "({}), which does not soften: ignored",
                        t.location("softening"), s.softening, s.self, t.location("self"));
        s.softening = 0.0;
    }
    s.allowLargeTheta = t.getOr<bool>("allow_large_theta", false);
    s.gradientOrder = t.getOrIf<int>(
        "gradient_order", 2, [](int o) { return o == 2 || o == 4; }, "2 or 4");
    s.poisson = t.getOrIf<std::string>(
        "poisson", s.poisson, [](std::string const& v) { return v == "petsc" || v == "fft"; },
        "\"petsc\" or \"fft\"");
    if (auto const petsc = t.findTable("petsc"))
        s.petscOptions = petsc->getOr<std::string>("options", "");
    s.p3mCutoff = t.getOrIf<double>(
        "p3m_cutoff", s.p3mCutoff, [](double c) { return c >= 2.0 && std::isfinite(c); },
        "a number of cells >= 2");
    s.gridSpacing = t.getOrIf<double>("grid_spacing", s.gridSpacing, isPositiveFinite,
                                      "a positive finite length");
    s.neighbourhood = t.getOrIf<double>("neighbourhood", s.neighbourhood, isNonNegativeFinite,
                                        "a non-negative finite length");
    return s;
}

namespace {

/// The sums over grains (direct, the trees, the paper's node methods) give the free-space
/// field of the grains as they lie, with no periodic images: across a periodic face, where
/// the contacts see neighbours, they would pull the two grains apart through the whole domain,
/// and the pull would jump when a grain crosses the face. Only the grid methods are periodic.
void requireGravityMatchesPeriodicity(core::ConfigTable const& root,
                                      SceneDescription const& scene) {
    auto const& periodic = scene.forest.periodic;
    std::string axes;
    for (std::size_t a = 0; a < 3; ++a)
        if (periodic[a])
            axes += std::string(axes.empty() ? "" : ", ") + "xyz"[a];
    std::string const& self = scene.gravity.self;
    coupling::GravityMethodEntry const* method = coupling::findGravityMethod(self);
    bool const freeSpace = method && !method->periodic;
    if (axes.empty() || !freeSpace)
        return;
    // Not the default (none): the key was written, so the section exists.
    root.findTable("gravity")->fail(
        "self",
        fmt::format("\"{}\" sums the grains' gravity in free space, without periodic "
                    "images, but domain.periodic makes {} periodic (grains across a "
                    "periodic face would attract each other through the whole domain); "
                    "use {} with every axis periodic, or an open domain",
                    self, axes, methodsWith(&coupling::GravityMethodEntry::periodic, " or ")));
}

} // namespace

SceneDescription parseScene(core::ConfigTable const& root, std::string const& scenePath) {
    SceneDescription scene;
    std::filesystem::path const source(scenePath);
    scene.name = root.getOrIf<std::string>(
        "name", scenePath.empty() ? std::string("default") : source.stem().string(),
        [](std::string const& n) { return !n.empty(); }, "a non-empty string");
    scene.forest = domain::parseForestSpec(root.table("domain"));
    scene.time = parseTime(root.table("time"));
    scene.sync = optionalSection<SyncSection>(root, "sync", parseSync);
    scene.contact = optionalSection<ContactSection>(root, "contact", parseContact);
    scene.materials = parseMaterials(root, scene.contact.elasticity);
    scene.gravity = optionalSection<GravitySection>(root, "gravity", parseGravity);
    scene.balance = optionalSection<BalanceSection>(root, "balance", parseBalance);
    scene.output = optionalSection<OutputSection>(root, "output", parseOutput);
    std::string const sceneDir = source.parent_path().string();
    auto const entries = root.tableArray("particles");
    for (auto const& entry : entries) {
        scene.particles.push_back(parseParticleSource(entry, scene.forest.domain, sceneDir));
        requireMaterial(scene.materials, entry, scene.particles.back().type);
    }
    auto const walls = root.tableArray("walls");
    for (std::size_t i = 0; i < walls.size(); ++i) {
        scene.walls.push_back(parseWall(walls[i], i));
        requireMaterial(scene.materials, walls[i], scene.walls.back().type);
    }
    for (auto const& entry : root.tableArray("insert")) {
        scene.inserts.push_back(parseInsert(entry, scene.forest));
        requireMaterial(scene.materials, entry, scene.inserts.back().type);
    }
    root.rejectUnknownKeys();
    requireGravityMatchesPeriodicity(root, scene);
    for (std::size_t i = 0; i < walls.size(); ++i)
        requireRepeatsAlongPeriodicAxes(walls[i], scene.walls[i], scene.forest);
    checkLattices(scene.particles, entries, scene.contact.initialOverlap, scene.forest);
    // The value rules of [[particles]] are the generators' (one place); checked here too so a
    // bad entry fails before anything is built, with the line it was written on.
    try {
        particles::validateParticleSpecs(
            scene.particles,
            particles::GeneratorDomain{scene.forest.domain, scene.forest.periodic});
    } catch (core::InputError const& e) {
        throw core::InputError(locateSceneKey(root, e.what()));
    }
    return scene;
}

std::string_view toString(particles::SyncMethod m) {
    return particles::syncMethodName(m);
}
std::string_view toString(Integrator i) {
    return kIntegratorNames[static_cast<std::size_t>(i)];
}

} // namespace regolith::apps
