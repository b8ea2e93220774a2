#include "particles/kernels/VanDerWaals.hpp"

#include "core/Error.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/config/ValueChecks.hpp"
#include "particles/kernels/MaterialMixing.hpp"
#include "particles/simulation/ContactModelRegistry.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string_view>
#include <utility>

namespace regolith::particles {

VanDerWaalsParams VanDerWaalsParams::fromScene(core::ConfigTable const& contact) {
    VanDerWaalsParams p;
    std::string_view const with = " (required with contact.model = \"vdw\")";
    p.hamaker =
        contact.getIf<double>("hamaker", core::isPositiveFinite,
                              fmt::format("a positive Hamaker constant A (an energy){}", with));
    p.minSeparation = contact.getIf<double>(
        "min_separation", core::isPositiveFinite,
        fmt::format("a positive minimum separation (a length, where the force stops growing){}",
                    with));
    p.cutoff = contact.getIf<double>(
        "cutoff", [&](double c) { return std::isfinite(c) && c > p.minSeparation; },
        fmt::format("a cut-off gap (a length) above min_separation = {:g}{}", p.minSeparation,
                    with));
    return p;
}

VanDerWaals::VanDerWaals(SpringDashpot repulsion, VanDerWaalsParams params)
    : m_repulsion(std::move(repulsion))
    , m_params(params) {
    if (!(params.hamaker > 0.0) || !(params.minSeparation > 0.0) ||
        !(params.cutoff > params.minSeparation) || !std::isfinite(params.hamaker) ||
        !std::isfinite(params.cutoff))
        throw core::InputError(fmt::format(
            "van der Waals cohesion: expected hamaker > 0, min_separation > 0 and cutoff > "
            "min_separation, got {:g}, {:g}, {:g}",
            params.hamaker, params.minSeparation, params.cutoff));
}

ContactModelEntry vanDerWaalsEntry() {
    return {"vdw", Elasticity::Linear,
            [](core::ConfigTable const& t) { (void)VanDerWaalsParams::fromScene(t); },
            [](ContactModelInputs const& in) {
                return AnyContactModel(VanDerWaals(
                    SpringDashpot(mixedTable<LinearContactParams>(in.types, in.rolling, mixLinear)),
                    VanDerWaalsParams::fromScene(in.contact)));
            }};
}

} // namespace regolith::particles
