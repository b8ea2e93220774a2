#pragma once
/// Per-grain fields of one's own (LAMMPS's `fix property/atom`): named values that every copy of
/// a grain carries besides the built-in state. Declared once per process, alike on every rank,
/// before the grains that use them are made; from then on the storage keeps one array per
/// component (ParticleStorage::field), the synchronisation sends the values with the grain (on
/// creation, migration and every update, so a shadow reads its master's), and checkpoints, VTK
/// output and particle snapshots write them as columns named after the field. A new per-grain
/// property is one declaration plus its use:
///
///     auto const temperature = particles::declareGrainField({"temperature", 1, "K", "..."});
///     ps.field(temperature, i) = 300.0;
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace regolith::particles {

struct GrainField {
    std::string name;        ///< letters, digits and '_', not a built-in column's name
    int components = 1;      ///< 1 (a scalar) or 3 (a vector)
    std::string unit = "1";  ///< written as the column's `units`
    std::string description; ///< written as the column's `description`
};

/// A declared field: its first component's place among all declared components.
struct GrainFieldId {
    std::uint32_t offset = 0;
    std::uint32_t components = 1;
};

/// Declares `field` and returns its id; declaring the same field again (same name, components
/// and unit) returns the first id. Throws core::Error for a bad name or component count, or a
/// name declared before with another shape. Not collective (declare alike on every rank).
GrainFieldId declareGrainField(GrainField const& field);
/// The declared fields, in declaration order.
[[nodiscard]] std::span<GrainField const> grainFields();
/// Their components together: the width of ParticleInit::fields.
[[nodiscard]] std::size_t grainFieldComponents();
/// The id of the declared field at `place` in grainFields().
[[nodiscard]] GrainFieldId grainFieldId(std::size_t place);

} // namespace regolith::particles
