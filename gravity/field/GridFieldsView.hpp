#pragma once
/// Read-only access to the cell fields of grid gravity on this rank's blocks, for output
/// (io/vtk writes them as image data): io sees the fields without knowing which coupling
/// object owns them. Local block b of the layout is forest().blocks()[b].
#include "gravity/field/CellField.hpp"
#include "gravity/field/CellLayout.hpp"

namespace regolith::gravity {

struct GridFieldsView {
    CellLayout const* layout = nullptr;
    CellField const* density = nullptr;      ///< mass per volume, 1 component
    CellField const* potential = nullptr;    ///< φ [length^2 / time^2], 1 component
    CellField const* acceleration = nullptr; ///< g = -∇φ [length / time^2], 3 components
};

} // namespace regolith::gravity
