#include "io/vtk/VtkSeries.hpp"

#include "core/Error.hpp"
#include "io/vtk/VtkModule.hpp"

namespace regolith::io {

std::vector<SeriesEntry> readSeries(std::string const& path) {
    std::vector<SeriesEntry> out;
    if (std::string const error = vtkxml::module().readCollection(path, out); !error.empty())
        throw core::InputError(error);
    return out;
}

} // namespace regolith::io
