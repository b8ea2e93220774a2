#include "domain/ForestConfig.hpp"

#include "domain/BlockId.hpp"
#include "domain/SpecValidation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>

namespace regolith::domain {

namespace {

bool finite(core::Vec3 const& v) {
    return v.allFinite();
}

std::string str(core::Vec3 const& v) {
    return fmt::format("[{}, {}, {}]", v[0], v[1], v[2]);
}

core::Vec3 finiteVec3(core::ConfigTable const& t, std::string_view key) {
    return t.getIf<core::Vec3>(key, finite, "an array of 3 finite numbers");
}

RefineRegion parseRefine(core::ConfigTable const& t, core::AABB const& domain) {
    RefineRegion r;
    r.region.min = finiteVec3(t, "min");
    r.region.max = finiteVec3(t, "max");
    r.level = t.getIf<int>(
        "level", [](int l) { return l >= 0 && l <= kMaxRefineLevel; },
        fmt::format("an integer in [0, {}]", kMaxRefineLevel));
    if (!(r.region.min.array() <= r.region.max.array()).all())
        t.fail("max", fmt::format("must not be below {}.min on any axis, got min = {}, max = {}",
                                  t.path(), str(r.region.min), str(r.region.max)));
    // With min <= max, the region is inside iff min is not below the domain and max not above.
    bool const minInside = (r.region.min.array() >= domain.min.array()).all();
    bool const maxInside = (r.region.max.array() <= domain.max.array()).all();
    if (!minInside || !maxInside)
        t.fail(minInside ? "max" : "min",
               fmt::format("the region {} - {} must lie inside the domain {} - {}",
                           str(r.region.min), str(r.region.max), str(domain.min), str(domain.max)));
    return r;
}

} // namespace

ForestSpec parseForestSpec(core::ConfigTable const& section) {
    ForestSpec spec;
    spec.domain.min = finiteVec3(section, "min");
    spec.domain.max = finiteVec3(section, "max");
    if (!(spec.domain.max.array() > spec.domain.min.array()).all())
        section.fail("max", fmt::format("must exceed domain.min on every axis, got min = {}, "
                                        "max = {}",
                                        str(spec.domain.min), str(spec.domain.max)));

    // Read as 64-bit integers, so that a count beyond int is told the limit, not the type.
    auto const blocks = section.getOrIf<std::array<std::int64_t, 3>>(
        "blocks", {1, 1, 1},
        [](auto const& n) {
            return std::all_of(n.begin(), n.end(), [](std::int64_t v) {
                return v > 0 && v <= std::int64_t{kMaxRootBlocksPerAxis};
            });
        },
        fmt::format("an array of 3 positive integers (at most {} each)", kMaxRootBlocksPerAxis));
    for (std::size_t a = 0; a < 3; ++a)
        spec.rootBlocks[a] = static_cast<int>(blocks[a]);
    spec.rootBlocksAuto = !section.has("blocks");
    std::uint64_t const total = static_cast<std::uint64_t>(spec.rootBlocks[0]) *
                                static_cast<std::uint64_t>(spec.rootBlocks[1]) *
                                static_cast<std::uint64_t>(spec.rootBlocks[2]);
    if (total > BlockId::kMaxRootIndex + 1)
        section.fail("blocks", fmt::format("at most {} root blocks in total, got {}",
                                           BlockId::kMaxRootIndex + 1, total));

    spec.periodic = section.getOr<std::array<bool, 3>>("periodic", {false, false, false});

    for (auto const& entry : section.tableArray("refine"))
        spec.refine.push_back(parseRefine(entry, spec.domain));

    spec.cellsPerBlock = section.getOrIf<std::array<int, 3>>(
        "cells_per_block", {0, 0, 0},
        [](auto const& c) {
            bool const allZero = c[0] == 0 && c[1] == 0 && c[2] == 0;
            bool const allPositive = c[0] > 0 && c[1] > 0 && c[2] > 0;
            return allZero || allPositive;
        },
        "an array of 3 integers, all positive (or all zero: no grid)");
    constexpr std::array<std::string_view, 2> kBalanceNames{"load", "blocks"};
    spec.balance =
        static_cast<ForestSpec::Balance>(section.getChoiceOr("balance", kBalanceNames, 0));
    spec.cellWeight = section.getOrIf<double>(
        "cell_weight", spec.cellWeight, [](double w) { return std::isfinite(w) && w >= 0.0; },
        "a non-negative finite number");

    validate(spec); // the module's own check; everything it rejects was reported above
    return spec;
}

} // namespace regolith::domain
