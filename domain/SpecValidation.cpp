#include "domain/SpecValidation.hpp"

#include "core/Error.hpp"
#include "domain/BlockId.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstdint>
#include <string>

namespace regolith::domain {

namespace {

std::string str(core::Vec3 const& v) {
    return fmt::format("[{}, {}, {}]", v[0], v[1], v[2]);
}

bool finite(core::Vec3 const& v) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

void checkExtent(ForestSpec const& spec) {
    core::AABB const& d = spec.domain;
    if (!finite(d.min))
        throw core::InputError("domain.min: expected finite numbers, got " + str(d.min));
    if (!finite(d.max))
        throw core::InputError("domain.max: expected finite numbers, got " + str(d.max));
    if (!(d.max.array() > d.min.array()).all())
        throw core::InputError("domain.max: expected max > min on every axis, got min = " +
                               str(d.min) + ", max = " + str(d.max));
}

void checkBlocks(ForestSpec const& spec) {
    auto const& n = spec.rootBlocks;
    for (int const v : n)
        if (v <= 0)
            throw core::InputError(
                fmt::format("domain.blocks: expected positive integers, got {}", n));
    for (int const v : n)
        if (v > kMaxRootBlocksPerAxis)
            throw core::InputError(
                fmt::format("domain.blocks: at most {} root blocks per axis, got {}",
                            kMaxRootBlocksPerAxis, n));
    std::uint64_t const total = static_cast<std::uint64_t>(n[0]) *
                                static_cast<std::uint64_t>(n[1]) * static_cast<std::uint64_t>(n[2]);
    if (total > BlockId::kMaxRootIndex + 1)
        throw core::InputError(fmt::format("domain.blocks: at most {} root blocks in total, got {} "
                                           "= {}",
                                           BlockId::kMaxRootIndex + 1, n, total));
}

void checkRefine(ForestSpec const& spec) {
    core::AABB const& d = spec.domain;
    for (std::size_t i = 0; i < spec.refine.size(); ++i) {
        RefineRegion const& r = spec.refine[i];
        if (r.level < 0 || r.level > kMaxRefineLevel)
            throw core::InputError(fmt::format("domain.refine[{}].level: expected an integer in "
                                               "[0, {}], got {}",
                                               i, kMaxRefineLevel, r.level));
        core::AABB const& g = r.region;
        bool const ok = finite(g.min) && finite(g.max) && (g.min.array() <= g.max.array()).all() &&
                        (g.min.array() >= d.min.array()).all() &&
                        (g.max.array() <= d.max.array()).all();
        if (!ok)
            throw core::InputError(fmt::format(
                "domain.refine[{}].region: expected min <= max inside the domain {} - {}, got {} - "
                "{}",
                i, str(d.min), str(d.max), str(g.min), str(g.max)));
    }
}

void checkCells(ForestSpec const& spec) {
    auto const& c = spec.cellsPerBlock;
    bool const allZero = c[0] == 0 && c[1] == 0 && c[2] == 0;
    bool const allPositive = c[0] > 0 && c[1] > 0 && c[2] > 0;
    if (!allZero && !allPositive)
        throw core::InputError(fmt::format(
            "domain.cells_per_block: expected three positive integers (or none), got {}", c));
}

} // namespace

void validate(ForestSpec const& spec) {
    checkExtent(spec);
    checkBlocks(spec);
    checkRefine(spec);
    checkCells(spec);
}

} // namespace regolith::domain
