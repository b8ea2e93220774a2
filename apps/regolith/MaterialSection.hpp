#pragma once
/// The scene's materials (docs/guide/scene.md, "[[materials]]"): per material type the contact
/// model's elasticity (spring-dashpot: stiffness; Hertz–Mindlin: youngs_modulus and
/// poisson_ratio, both required), restitution, friction and rolling friction. Without
/// [[materials]] the same keys in [contact] make the one material of every type (the scenes
/// before materials existed). Unlike pairs mix by particles/kernels/MaterialMixing.hpp.
#include "core/config/ConfigTable.hpp"
#include "particles/kernels/MaterialMixing.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::apps {

struct MaterialsSection {
    /// [[materials]] in type order (entry k is type k unless it says `type`), or the [contact]
    /// material alone.
    std::vector<particles::MaterialProperties> types;
    bool perType = false; ///< from [[materials]]; else types[0] is every type's
    /// The properties of material `type` (< types.size() when perType).
    [[nodiscard]] particles::MaterialProperties const& of(std::uint32_t type) const {
        return types[perType ? type : 0];
    }
};

/// The material keys of one table ([contact] or a [[materials]] entry) for a contact model of
/// `elasticity`: stiffness (> 0, default 1e4) with Linear (spring-dashpot, vdw), youngs_modulus
/// (> 0) and poisson_ratio (in (-1, 0.5]) required with Hertz (hertz, dmt) (the keys of the other
/// model refused, naming the right ones), restitution in (0, 1] (0.9), friction >= 0 (0.5),
/// rolling_friction >= 0 (0). Throws core::InputError naming the key. Not collective.
[[nodiscard]] particles::MaterialProperties parseMaterialKeys(core::ConfigTable const& t,
                                                              particles::Elasticity elasticity);

/// The scene's materials from `root`'s [[materials]] (an optional `type` per entry: the types
/// 0 to n-1, each once; the material keys of [contact] are then refused) or [contact].
/// Not collective.
[[nodiscard]] MaterialsSection parseMaterials(core::ConfigTable const& root,
                                              particles::Elasticity elasticity);

/// Refuses a `type` of a [[particles]] or [[walls]] entry (`entry`, whose parsed type is
/// `type`) that no [[materials]] entry defines. Not collective.
void requireMaterial(MaterialsSection const& materials, core::ConfigTable const& entry,
                     std::uint32_t type);

} // namespace regolith::apps
