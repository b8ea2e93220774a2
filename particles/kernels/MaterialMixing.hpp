#pragma once
/// The contact parameters of every pair of material types from the properties of each type,
/// by the mixing rules of LAMMPS's pair_style granular (docs.lammps.org/pair_granular.html,
/// "Mixing"): the effective elastic moduli of Hertz–Mindlin from both Young's moduli and
/// Poisson ratios (HertzMindlinParams::fromMaterials), every other coefficient (the linear
/// stiffness, restitution, friction, rolling friction) the geometric mean sqrt(c_a c_b), which
/// is c itself for a like pair.
#include "particles/kernels/HertzMindlin.hpp"
#include "particles/kernels/MaterialTable.hpp"
#include "particles/kernels/SpringDashpot.hpp"
#include "particles/kernels/TangentialSpring.hpp"

#include <span>

namespace regolith::particles {

/// Which elastic keys of a material a contact model reads: the linear spring's stiffness, or
/// Hertz's Young's modulus and Poisson ratio.
enum class Elasticity { Linear, Hertz };

/// One material type's properties (the scene's [[materials]] entry).
struct MaterialProperties {
    double stiffness = 0.0;     ///< k_n of the linear model [force/length]
    double youngsModulus = 0.0; ///< E of Hertz–Mindlin [pressure]
    double poissonRatio = 0.0;  ///< nu of Hertz–Mindlin, in (-1, 0.5]
    double restitution = 1.0;   ///< in (0, 1]
    double friction = 0.0;      ///< Coulomb mu >= 0
    double rollingFriction = 0.0;
};

/// sqrt(a b), exactly a when a == b.
[[nodiscard]] double geometricMean(double a, double b);

/// The linear model's pair (a, b): k_n, e, mu, mu_r the geometric means, k_t = 2/7 k_n
/// (normal and tangential periods equal), `rolling` (model C's settings, shared by all pairs).
[[nodiscard]] LinearContactParams
mixLinear(MaterialProperties const& a, MaterialProperties const& b, RollingSpring const& rolling);
/// Hertz–Mindlin's pair (a, b): E* and G* from E and nu of both (fromMaterials), e, mu, mu_r
/// the geometric means. Throws core::InputError for E <= 0 or nu outside (-1, 0.5].
[[nodiscard]] HertzMindlinParams mixHertz(MaterialProperties const& a, MaterialProperties const& b,
                                          RollingSpring const& rolling);

/// The table of every pair of `types.size()` types (type t has `types[t]`) with `mix`.
template <class P, class Mix>
[[nodiscard]] MaterialTable<P> mixedTable(std::span<MaterialProperties const> types,
                                          RollingSpring const& rolling, Mix mix) {
    MaterialTable<P> table(types.size());
    for (std::uint32_t a = 0; a < types.size(); ++a)
        for (std::uint32_t b = a; b < types.size(); ++b)
            table.set(a, b, mix(types[a], types[b], rolling));
    return table;
}

} // namespace regolith::particles
