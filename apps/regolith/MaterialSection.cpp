#include "apps/regolith/MaterialSection.hpp"

#include "core/config/ValueChecks.hpp"

#include <fmt/format.h>

#include <array>
#include <optional>
#include <string_view>

namespace regolith::apps {

namespace {

using namespace std::string_view_literals;

/// The keys a material sets (in [contact] without [[materials]]).
constexpr std::array kMaterialKeys{"stiffness"sv,   "youngs_modulus"sv, "poisson_ratio"sv,
                                   "restitution"sv, "friction"sv,       "rolling_friction"sv};

} // namespace

particles::MaterialProperties parseMaterialKeys(core::ConfigTable const& t,
                                                particles::Elasticity elasticity) {
    particles::MaterialProperties m;
    if (elasticity == particles::Elasticity::Linear) {
        for (char const* key : {"youngs_modulus", "poisson_ratio"})
            if (t.has(key))
                t.fail(key, "applies to contact.model = \"hertz\"; the spring-dashpot model's "
                            "elasticity is stiffness (force / length)");
        m.stiffness =
            t.getOrIf<double>("stiffness", 1e4, core::isPositiveFinite, "a positive finite number");
    } else {
        if (t.has("stiffness")) {
            double const old = t.getOr<double>("stiffness", 0.0);
            t.fail("stiffness",
                   fmt::format("with contact.model = \"hertz\" a material's elasticity is "
                               "youngs_modulus (E, a pressure) and poisson_ratio (nu), both "
                               "required (two like grains have the effective modulus "
                               "E / (2 (1 - nu^2))); stiffness = {0:g} as the effective "
                               "modulus with nu = 0.3 is youngs_modulus = {1:g}, "
                               "poisson_ratio = 0.3",
                               old, 2.0 * (1.0 - 0.3 * 0.3) * old));
        }
        std::string_view const required = ", required with contact.model = \"hertz\"";
        for (auto const& [key, what] : {std::pair("youngs_modulus", "Young's modulus, > 0"),
                                        std::pair("poisson_ratio", "Poisson ratio, in (-1, 0.5]")})
            if (!t.has(key))
                t.fail(key, fmt::format("is required with contact.model = \"hertz\" (the "
                                        "material's {})",
                                        what));
        m.youngsModulus = t.getIf<double>(
            "youngs_modulus", core::isPositiveFinite,
            fmt::format("a positive finite Young's modulus (a pressure){}", required));
        m.poissonRatio = t.getIf<double>(
            "poisson_ratio", [](double nu) { return nu > -1.0 && nu <= 0.5; },
            fmt::format("a Poisson ratio in (-1, 0.5]{}", required));
    }
    m.restitution = t.getOrIf<double>(
        "restitution", 0.9, [](double e) { return e > 0.0 && e <= 1.0; }, "a number in (0, 1]");
    m.friction = t.getOrIf<double>("friction", 0.5, core::isNonNegativeFinite,
                                   "a non-negative finite number");
    m.rollingFriction = t.getOrIf<double>("rolling_friction", 0.0, core::isNonNegativeFinite,
                                          "a non-negative finite number");
    return m;
}

MaterialsSection parseMaterials(core::ConfigTable const& root, particles::Elasticity elasticity) {
    auto const entries = root.tableArray("materials");
    std::optional<core::ConfigTable> const contact = root.findTable("contact");
    MaterialsSection s;
    if (entries.empty()) {
        s.types.push_back(
            contact ? parseMaterialKeys(*contact, elasticity)
                    : parseMaterialKeys(core::ConfigTable::fromString("", ""), elasticity));
        return s;
    }
    if (contact)
        for (std::string_view key : kMaterialKeys)
            if (contact->has(key))
                contact->fail(key, "is set per material type in [[materials]] when the scene "
                                   "has them; move it there");
    s.perType = true;
    s.types.resize(entries.size());
    std::vector<int> given(entries.size(), -1); // the entry that defined each type
    for (std::size_t k = 0; k < entries.size(); ++k) {
        auto const n = static_cast<std::int64_t>(entries.size());
        auto const type = entries[k].getOrIf<std::int64_t>(
            "type", static_cast<std::int64_t>(k), [n](std::int64_t t) { return t >= 0 && t < n; },
            fmt::format("a material type from 0 to {} (one [[materials]] entry each)", n - 1));
        auto const at = static_cast<std::size_t>(type);
        if (given[at] >= 0)
            entries[k].fail("type",
                            fmt::format("type {} is already materials[{}]'s", type, given[at]));
        given[at] = static_cast<int>(k);
        s.types[at] = parseMaterialKeys(entries[k], elasticity);
    }
    return s;
}

void requireMaterial(MaterialsSection const& materials, core::ConfigTable const& entry,
                     std::uint32_t type) {
    if (!materials.perType || type < materials.types.size())
        return;
    entry.fail("type", fmt::format("no [[materials]] entry has type {} (the scene defines types "
                                   "0 to {})",
                                   type, materials.types.size() - 1));
}

} // namespace regolith::apps
