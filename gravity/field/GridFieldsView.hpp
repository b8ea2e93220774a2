#pragma once
/// Read-only access to cell fields on this rank's blocks, for output (io/vtk writes them as
/// image data): io sees the fields without knowing who owns them, grid gravity's (density,
/// potential, acceleration) or a program's own. Local block b of the layout is
/// forest().blocks()[b].
#include "gravity/field/CellField.hpp"
#include "gravity/field/CellLayout.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace regolith::gravity {

/// A field with the name its VTK cell array gets (1 or 3 components: a scalar or a vector).
struct NamedCellField {
    std::string name;
    CellField const* field = nullptr;
};

struct GridFieldsView {
    CellLayout const* layout = nullptr;
    std::vector<NamedCellField> fields; ///< each on `layout`, written in this order

    /// The field called `name`, or nullptr.
    [[nodiscard]] CellField const* find(std::string_view name) const {
        for (NamedCellField const& f : fields)
            if (f.name == name)
                return f.field;
        return nullptr;
    }
};

} // namespace regolith::gravity
