#include "io/vtk/GridPieces.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkXMLImageDataWriter.h>

namespace regolith::io::detail {

std::vector<ArraySpec> gridArrays() {
    return {{"density", "Float64", 1}, {"potential", "Float64", 1}, {"acceleration", "Float64", 3}};
}

namespace {

/// The interior cells of every component of `field` on block b, x fastest (VTK's cell
/// order), as one array.
vtkNew<vtkDoubleArray> interiorCells(char const* name, gravity::CellField const& field,
                                     std::size_t b) {
    auto const& n = field.layout().cellsPerBlock();
    int const components = field.components();
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(components);
    a->SetNumberOfTuples(static_cast<vtkIdType>(field.layout().cellsInBlock()));
    double* out = a->GetPointer(0); // tuples interleaved: components per cell
    for (int c = 0; c < components; ++c) {
        std::size_t t = static_cast<std::size_t>(c);
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i, t += static_cast<std::size_t>(components))
                    out[t] = field.at(b, i, j, k, c);
    }
    return a;
}

} // namespace

void writeGridPiece(std::string const& path, gravity::GridFieldsView const& fields, std::size_t b) {
    gravity::CellLayout const& layout = *fields.layout;
    auto const& n = layout.cellsPerBlock();
    core::Vec3 const& corner = layout.forest().blocks()[b].aabb.min;
    vtkNew<vtkImageData> image;
    image->SetDimensions(n[0] + 1, n[1] + 1, n[2] + 1); // points: one more than cells
    image->SetOrigin(corner.x(), corner.y(), corner.z());
    image->SetSpacing(layout.spacing().x(), layout.spacing().y(), layout.spacing().z());
    vtkCellData* cd = image->GetCellData();
    cd->AddArray(interiorCells("density", *fields.density, b));
    cd->AddArray(interiorCells("potential", *fields.potential, b));
    cd->AddArray(interiorCells("acceleration", *fields.acceleration, b));
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(image);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff(); // raw binary, as the particle pieces
    writer->SetHeaderTypeToUInt64();
    if (writer->Write() != 1)
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
