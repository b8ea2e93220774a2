#include "io/vtk/GridPieces.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

namespace regolith::io::detail {

std::vector<ArraySpec> gridArrays() {
    return {{"density", "Float64", 1}, {"potential", "Float64", 1}, {"acceleration", "Float64", 3}};
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
    std::vector<double> const density = interiorCells(*fields.density, b);
    std::vector<double> const potential = interiorCells(*fields.potential, b);
    std::vector<double> const acceleration = interiorCells(*fields.acceleration, b);
    std::vector<ArraySpec> const specs = gridArrays();
    std::vector<vtkxml::Column> const columns{
        {specs[0], density.data()}, {specs[1], potential.data()}, {specs[2], acceleration.data()}};
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
