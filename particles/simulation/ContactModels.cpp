// The built-in contact models a scene names (contact.model): one registration line each. A
// model's entry (name, elasticity, key check, factory) is in its own file; the two elastic
// models' are here, their kernels being older than the registry.
#include "particles/kernels/Dmt.hpp"
#include "particles/kernels/HertzMindlin.hpp"
#include "particles/kernels/MaterialMixing.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/kernels/VanDerWaals.hpp"
#include "particles/simulation/ContactModelRegistry.hpp"

namespace regolith::particles {

namespace {

ContactModelEntry springDashpotEntry() {
    return {"spring-dashpot", Elasticity::Linear, {}, [](ContactModelInputs const& in) {
                return AnyContactModel(SpringDashpot(
                    mixedTable<LinearContactParams>(in.types, in.rolling, mixLinear)));
            }};
}

ContactModelEntry hertzEntry() {
    return {"hertz", Elasticity::Hertz, {}, [](ContactModelInputs const& in) {
                return AnyContactModel(
                    HertzMindlin(mixedTable<HertzMindlinParams>(in.types, in.rolling, mixHertz)));
            }};
}

} // namespace

void addBuiltInContactModels(ContactModelRegistry& registry) {
    registry.add(springDashpotEntry());
    registry.add(hertzEntry());
    registry.add(vanDerWaalsEntry());
    registry.add(dmtEntry());
}

} // namespace regolith::particles
