#include "particles/kernels/Dmt.hpp"

#include "core/Error.hpp"
#include "core/config/ConfigTable.hpp"
#include "core/config/ValueChecks.hpp"
#include "particles/kernels/MaterialMixing.hpp"
#include "particles/simulation/ContactModelRegistry.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

namespace regolith::particles {

Dmt::Dmt(HertzMindlin elastic, double surfaceEnergy)
    : m_elastic(std::move(elastic))
    , m_surfaceEnergy(surfaceEnergy) {
    if (!(surfaceEnergy >= 0.0) || !std::isfinite(surfaceEnergy))
        throw core::InputError(
            fmt::format("DMT adhesion: expected a surface energy >= 0, got {:g}", surfaceEnergy));
}

double Dmt::surfaceEnergyFromScene(core::ConfigTable const& contact) {
    return contact.getIf<double>("surface_energy", core::isNonNegativeFinite,
                                 "a non-negative surface energy gamma (energy / area; the pull-off "
                                 "force is 2 pi gamma R*), required with contact.model = \"dmt\"");
}

ContactModelEntry dmtEntry() {
    return {"dmt", Elasticity::Hertz,
            [](core::ConfigTable const& t) { (void)Dmt::surfaceEnergyFromScene(t); },
            [](ContactModelInputs const& in) {
                return AnyContactModel(Dmt(
                    HertzMindlin(mixedTable<HertzMindlinParams>(in.types, in.rolling, mixHertz)),
                    Dmt::surfaceEnergyFromScene(in.contact)));
            }};
}

} // namespace regolith::particles
