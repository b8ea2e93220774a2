#include "io/vtk/GridPieces.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

namespace regolith::io::detail {

std::vector<ArraySpec> gridArrays(gravity::GridFieldsView const& fields) {
    std::vector<ArraySpec> specs;
    for (gravity::NamedCellField const& f : fields.fields)
        specs.push_back({f.name, "Float64", f.field != nullptr ? f.field->components() : 1});
    return specs;
}

namespace {

/// The interior cells of every component of `field` on block b, x fastest (VTK's cell
/// order), components interleaved per cell.
std::vector<double> interiorCells(gravity::CellField const& field, std::size_t b) {
    auto const& n = field.layout().cellsPerBlock();
    auto const components = static_cast<std::size_t>(field.components());
    std::vector<double> out(field.layout().cellsInBlock() * components);
    for (std::size_t c = 0; c < components; ++c) {
        std::size_t t = c;
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i, t += components)
                    out[t] = field.at(b, i, j, k, static_cast<int>(c));
    }
    return out;
}

} // namespace

void writeGridPiece(std::string const& path, gravity::GridFieldsView const& fields, std::size_t b) {
    gravity::CellLayout const& layout = *fields.layout;
    core::Vec3 const& corner = layout.forest().blocks()[b].aabb.min;
    core::Vec3 const& h = layout.spacing();
    std::vector<ArraySpec> const specs = gridArrays(fields);
    std::vector<std::vector<double>> cells;
    std::vector<vtkxml::Column> columns;
    cells.reserve(specs.size());
    for (std::size_t f = 0; f < specs.size(); ++f) {
        gravity::CellField const* field = fields.fields[f].field;
        if (field == nullptr)
            throw core::Error(fmt::format("grid field '{}' has no cells", specs[f].name));
        cells.push_back(interiorCells(*field, b));
        columns.push_back({specs[f], cells.back().data()});
    }
    if (!vtkxml::module().writeImage(path, layout.cellsPerBlock(),
                                     {corner.x(), corner.y(), corner.z()}, {h.x(), h.y(), h.z()},
                                     columns))
        throw core::Error(fmt::format("cannot write VTK file '{}'", path));
}

std::string vtmText(std::vector<BlockPiece> const& pieces) {
    std::string out = "<?xml version=\"1.0\"?>\n"
                      "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" "
                      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                      "  <vtkMultiBlockDataSet>\n";
    for (std::size_t k = 0; k < pieces.size(); ++k)
        out += fmt::format("    <DataSet index=\"{}\" name=\"{}\" file=\"{}\"/>\n", k,
                           pieces[k].name, pieces[k].file);
    out += "  </vtkMultiBlockDataSet>\n</VTKFile>\n";
    return out;
}

} // namespace regolith::io::detail
