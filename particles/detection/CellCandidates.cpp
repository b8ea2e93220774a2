#include "particles/detection/CellCandidates.hpp"

#include <algorithm>

namespace regolith::particles::cells_detail {

bool cellLanesAvailable() {
    static bool const available = [] {
        __builtin_cpu_init();
        // The lane code generation's instruction sets (cmake/RegolithTargets.cmake).
        return cellLanesCompiled() && __builtin_cpu_supports("avx512f") != 0 &&
               __builtin_cpu_supports("avx512vl") != 0 && __builtin_cpu_supports("avx512dq") != 0;
    }();
    return available;
}

void appendCellOverlaps(SphereLanes const& lanes, SlotRange own, std::span<SlotRange const> forward,
                        double slack, CellScratch& scratch, std::vector<SlotPair>& out) {
    if (cellLanesAvailable())
        appendCellOverlapsInLanes(lanes, own, forward, slack, scratch, out);
    else
        appendCellOverlapsOneByOne(lanes, own, forward, slack, out);
}

void appendCellOverlapsOneByOne(SphereLanes const& lanes, SlotRange own,
                                std::span<SlotRange const> forward, double slack,
                                std::vector<SlotPair>& out) {
    auto each = [&](std::uint32_t t0, std::uint32_t t1) {
        for (std::uint32_t s = own.begin; s < own.end; ++s) {
            auto const xs = static_cast<double>(lanes.x[s]);
            auto const ys = static_cast<double>(lanes.y[s]);
            auto const zs = static_cast<double>(lanes.z[s]);
            auto const rs = static_cast<double>(lanes.radius[s]);
            for (std::uint32_t t = std::max(t0, s + 1); t < t1; ++t) {
                double const dx = static_cast<double>(lanes.x[t]) - xs;
                double const dy = static_cast<double>(lanes.y[t]) - ys;
                double const dz = static_cast<double>(lanes.z[t]) - zs;
                double const d2 = dx * dx + dy * dy + dz * dz;
                double const reach = rs + static_cast<double>(lanes.radius[t]) + slack;
                if (d2 < reach * reach)
                    out.push_back(SlotPair{s, t, d2});
            }
        }
    };
    each(own.begin, own.end);
    for (SlotRange const& r : forward)
        each(r.begin, r.end);
}

} // namespace regolith::particles::cells_detail
