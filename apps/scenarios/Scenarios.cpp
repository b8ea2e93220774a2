#include "apps/scenarios/Scenarios.hpp"

#include "apps/scenarios/RankGrid.hpp"
#include "core/Error.hpp"
#include "core/log/Log.hpp"
#include "domain/BlockId.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace regolith::apps {

namespace {

using Vec = std::array<double, 3>;
using Counts = std::array<std::int64_t, 3>;

/// A TOML float (never an integer literal: "20.0", not "20").
std::string num(double v) {
    std::string s = fmt::format("{}", v);
    if (s.find_first_of(".eEn") == std::string::npos)
        s += ".0";
    return s;
}
std::string list(Vec const& v) {
    return fmt::format("[{}, {}, {}]", num(v[0]), num(v[1]), num(v[2]));
}
std::string list(Counts const& v) {
    return fmt::format("[{}, {}, {}]", v[0], v[1], v[2]);
}

/// Sets `key` = `value` (TOML), attributing it to the scenario key that decided it.
void set(core::ConfigTable& scene, std::string_view key, std::string const& value,
         std::string_view because) {
    scene.applyOverride(fmt::format("{}={}", key, value),
                        fmt::format("{} (from {})", key, because));
}

/// The domain keys the expansion owns must not be set by the scene; `instead` names the
/// scenario's keys that decide them.
void requireDomainUnset(core::ConfigTable const& scene, std::string_view section,
                        std::string_view instead) {
    auto const domain = scene.findTable("domain");
    for (std::string_view key : {"max", "blocks"})
        if (domain && domain->has(key))
            domain->fail(key, fmt::format("is set by the [{}] scenario; change {} instead", section,
                                          instead));
}

/// A key the expansion overwrites (in `table`, the scene's or an array element's) must not be
/// set by the user: by --set ever, in the file unless `fileMayHold` (a scene file's placeholder
/// the expansion moves, as dense-ramp.toml's upper wall). `instead` names the scenario's keys
/// that decide it.
void requireNotSetByUser(std::optional<core::ConfigTable> const& table, std::string_view key,
                         std::string_view section, std::string_view instead, bool fileMayHold) {
    if (!table || !table->has(key))
        return;
    if (fileMayHold && !table->location(key).starts_with("--set"))
        return;
    table->fail(key,
                fmt::format("is set by the [{}] scenario; change {} instead", section, instead));
}

/// Element `index` of the scene's array of tables `key`, if there is one.
std::optional<core::ConfigTable> element(core::ConfigTable const& scene, std::string_view key,
                                         std::size_t index) {
    if (scene.kindOf(key) == core::ConfigKind::Missing)
        return std::nullopt;
    std::vector<core::ConfigTable> all = scene.tableArray(key);
    if (index >= all.size())
        return std::nullopt;
    return all[index];
}

Counts positiveCounts(core::ConfigTable const& s, std::string_view key, Counts fallback) {
    if (!s.has(key))
        return fallback;
    auto const v = s.get<Counts>(key);
    for (auto const c : v)
        if (c < 1)
            s.failExpected(key, "three integers >= 1");
    return v;
}

Vec positiveExtent(core::ConfigTable const& s, std::string_view key, Vec fallback) {
    if (!s.has(key))
        return fallback;
    auto const v = s.get<Vec>(key);
    for (auto const c : v)
        if (!(c > 0.0) || !std::isfinite(c))
            s.failExpected(key, "three positive lengths");
    return v;
}

/// Domain max and blocks of a weak or strong scaling layout on the rank grid; returns the
/// domain extent.
Vec layOut(core::ConfigTable& scene, std::string_view section, int ranks, int axes,
           Vec perRankDefault) {
    core::ConfigTable const s = scene.table(section);
    requireDomainUnset(scene, section,
                       fmt::format("{0}.per_rank, {0}.box or {0}.blocks_per_rank", section));
    static constexpr std::array<std::string_view, 2> kScaling{"weak", "strong"};
    bool const weak = s.getChoiceOr("scaling", kScaling, 0) == 0;
    auto const grid = rankGrid(ranks, axes);
    Vec const perRank = positiveExtent(s, "per_rank", perRankDefault);
    Vec extent{};
    for (std::size_t a = 0; a < 3; ++a)
        extent[a] = perRank[a] * grid[a];
    if (weak && s.has("box"))
        s.fail("box", "applies only with scaling = \"strong\" (weak scaling takes the extent "
                      "from per_rank and the rank count)");
    if (!weak) {
        if (!s.has("box"))
            s.fail("box", "is required with scaling = \"strong\" (the fixed domain extent)");
        extent = positiveExtent(s, "box", extent);
        // The scene files give per_rank for their weak default; only an explicit --set of it
        // with strong scaling is a request that goes unheard.
        if (s.location("per_rank").starts_with("--set"))
            core::log::warn("{}: {}: is ignored with scaling = \"strong\" ({} sets the extent)",
                            s.location("per_rank"), s.keyPath("per_rank"), s.keyPath("box"));
    }
    Counts const perRankBlocks = positiveCounts(s, "blocks_per_rank", {1, 1, 1});
    Counts blocks{};
    for (std::size_t a = 0; a < 3; ++a)
        blocks[a] = perRankBlocks[a] * grid[a];
    Vec const min = scene.table("domain").getOr<Vec>("min", Vec{0.0, 0.0, 0.0});
    Vec max{};
    for (std::size_t a = 0; a < 3; ++a)
        max[a] = min[a] + extent[a];
    std::string const why =
        fmt::format("{}.scaling = \"{}\" on {} ranks", section, weak ? "weak" : "strong", ranks);
    set(scene, "domain.max", list(max), why);
    set(scene, "domain.blocks", list(blocks), why);
    return extent;
}

} // namespace

void expandGranularGas(core::ConfigTable& scene, int ranks) {
    if (scene.findTable("granular_gas"))
        layOut(scene, "granular_gas", ranks, 3, {20.0, 20.0, 20.0});
}

void expandDenseRamp(core::ConfigTable& scene, int ranks) {
    if (!scene.findTable("dense_ramp"))
        return;
    Vec const extent = layOut(scene, "dense_ramp", ranks, 2, {20.0, 10.0 * std::sqrt(3.0), 8.0});
    core::ConfigTable const s = scene.table("dense_ramp");
    double const g = s.getOrIf<double>(
        "gravity", 1.0, [](double v) { return v >= 0.0 && std::isfinite(v); },
        "a non-negative acceleration");
    double const degrees = s.getOrIf<double>(
        "inclination", 30.0, [](double v) { return v >= 0.0 && v < 90.0; },
        "an angle in [0, 90) degrees");
    double const angle = degrees * std::numbers::pi / 180.0;
    requireNotSetByUser(scene.findTable("gravity"), "external", "dense_ramp",
                        "dense_ramp.gravity or dense_ramp.inclination", false);
    requireNotSetByUser(element(scene, "walls", 1), "point", "dense_ramp",
                        "dense_ramp.per_rank or dense_ramp.box", true);
    set(scene, "gravity.external", list(Vec{g * std::sin(angle), 0.0, -g * std::cos(angle)}),
        "dense_ramp.inclination");
    double const zMin = scene.table("domain").getOr<Vec>("min", Vec{0.0, 0.0, 0.0})[2];
    set(scene, "walls[1].point", list(Vec{0.0, 0.0, zMin + extent[2]}), "dense_ramp.per_rank");
}

void expandBidisperse(core::ConfigTable& scene, int /*ranks*/) {
    if (!scene.findTable("bidisperse"))
        return;
    core::ConfigTable const s = scene.table("bidisperse");
    requireDomainUnset(scene, "bidisperse",
                       "bidisperse.building_blocks, bidisperse.blocks_per_building_block or "
                       "bidisperse.edge");
    Counts const count = positiveCounts(s, "building_blocks", {1, 1, 1});
    Counts const split = positiveCounts(s, "blocks_per_building_block", {4, 4, 4});
    // Bounded before the large spheres are written out one per building block below (10^15
    // of them exhausted the memory before domain.blocks was checked): every building block
    // is that many root blocks. In double: exact up to 2^53, far above the bound.
    double const rootBlocks = static_cast<double>(count[0]) * static_cast<double>(count[1]) *
                              static_cast<double>(count[2]) * static_cast<double>(split[0]) *
                              static_cast<double>(split[1]) * static_cast<double>(split[2]);
    double const maxRootBlocks = static_cast<double>(domain::BlockId::kMaxRootIndex) + 1.0;
    if (!(rootBlocks <= maxRootBlocks))
        s.fail("building_blocks",
               fmt::format("{} x {} x {} building blocks of {} x {} x {} root blocks each exceed "
                           "the forest's {} root blocks",
                           count[0], count[1], count[2], split[0], split[1], split[2],
                           maxRootBlocks));
    double const edge = s.getOrIf<double>(
        "edge", 80.0, [](double v) { return v > 0.0 && std::isfinite(v); }, "a positive length");
    double const radius = s.getOrIf<double>(
        "large_radius", 15.0, [edge](double v) { return v > 0.0 && v < 0.5 * edge; },
        "a radius above 0 and below half the building-block edge");
    Vec const min = scene.table("domain").getOr<Vec>("min", Vec{0.0, 0.0, 0.0});
    Vec max{};
    Counts blocks{};
    for (std::size_t a = 0; a < 3; ++a) {
        max[a] = min[a] + edge * static_cast<double>(count[a]);
        blocks[a] = count[a] * split[a];
    }
    std::string const why = "bidisperse.building_blocks";
    std::optional<core::ConfigTable> const large = element(scene, "particles", 0);
    if (!large || !large->has("kind") || large->getString("kind") != "list")
        throw core::InputError(fmt::format(
            "{}: particles[0]: the [bidisperse] scenario places its large spheres in the first "
            "[[particles]] entry, which must be kind = \"list\"",
            large ? large->location() : scene.location()));
    for (std::string_view key : {"position", "radius"})
        requireNotSetByUser(large, key, "bidisperse",
                            key == "radius" ? "bidisperse.large_radius"
                                            : "bidisperse.building_blocks or bidisperse.edge",
                            true);
    set(scene, "domain.max", list(max), why);
    set(scene, "domain.blocks", list(blocks), "bidisperse.blocks_per_building_block");
    std::string positions;
    std::string radii;
    for (std::int64_t k = 0; k < count[2]; ++k)
        for (std::int64_t j = 0; j < count[1]; ++j)
            for (std::int64_t i = 0; i < count[0]; ++i) {
                Vec const centre{min[0] + edge * (static_cast<double>(i) + 0.5),
                                 min[1] + edge * (static_cast<double>(j) + 0.5),
                                 min[2] + edge * (static_cast<double>(k) + 0.5)};
                positions += (positions.empty() ? "" : ", ") + list(centre);
                radii += (radii.empty() ? "" : ", ") + num(radius);
            }
    set(scene, "particles[0].position", "[" + positions + "]", why);
    set(scene, "particles[0].radius", "[" + radii + "]", "bidisperse.large_radius");
}

namespace {

/// Where a scenario section was given: the --set of one of its keys if a --set made it (its
/// table then has no place of its own), else the table's place in the file.
std::string sectionLocation(core::ConfigTable const& section) {
    for (std::string_view key :
         {"scaling", "per_rank", "box", "blocks_per_rank", "gravity", "inclination",
          "building_blocks", "blocks_per_building_block", "edge", "large_radius"})
        if (section.has(key) && section.location(key).starts_with("--set"))
            return section.location(key);
    return section.location();
}

} // namespace

void expandScenarios(core::ConfigTable& scene, int ranks) {
    // Each lays out the whole domain: two would overwrite each other's. The one named is the
    // one a --set added, if any.
    std::vector<std::string_view> present;
    for (std::string_view section : {"granular_gas", "dense_ramp", "bidisperse"})
        if (scene.findTable(section))
            present.push_back(section);
    if (present.size() > 1) {
        auto const added = std::find_if(present.begin(), present.end(), [&](std::string_view s) {
            return sectionLocation(scene.table(s)).starts_with("--set");
        });
        std::string_view const extra = added != present.end() ? *added : present[1];
        std::string_view const other = extra == present[0] ? present[1] : present[0];
        throw core::InputError(
            fmt::format("{}: [{}]: a scene takes one scenario section, and [{}] is one already",
                        sectionLocation(scene.table(extra)), extra, other));
    }
    expandGranularGas(scene, ranks);
    expandDenseRamp(scene, ranks);
    expandBidisperse(scene, ranks);
}

} // namespace regolith::apps
