#include "io/vtk/VtkSeries.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>
#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <filesystem>

namespace regolith::io {

std::vector<SeriesEntry> readSeries(std::string const& path) {
    vtkNew<vtkXMLDataParser> parser;
    parser->SetFileName(path.c_str());
    if (!std::filesystem::is_regular_file(path) || parser->Parse() != 1)
        throw core::InputError(fmt::format("cannot read the VTK series '{}'", path));
    vtkXMLDataElement* root = parser->GetRootElement();
    vtkXMLDataElement* collection = root ? root->FindNestedElementWithName("Collection") : nullptr;
    if (collection == nullptr)
        throw core::InputError(fmt::format("'{}' is not a VTK collection (.pvd)", path));
    std::vector<SeriesEntry> out;
    for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement* set = collection->GetNestedElement(i);
        char const* file = set->GetAttribute("file");
        double time = 0.0;
        if (file == nullptr || set->GetScalarAttribute("timestep", time) == 0)
            throw core::InputError(
                fmt::format("'{}': DataSet {} has no file or timestep", path, i));
        out.push_back({time, file});
    }
    return out;
}

} // namespace regolith::io
