// The VTK side of io/vtk (VtkModule.hpp), built as the shared module libregolith_vtk.so. The
// callers' arrays are wrapped, not copied (VTK only reads them while writing).
#include "io/vtk/VtkModule.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <vtkXMLWriter.h>

#include <filesystem>
#include <stdexcept>

namespace regolith::io::vtkxml {

namespace {

int vtkTypeOf(std::string const& type) {
    if (type == "Float64")
        return VTK_DOUBLE;
    if (type == "Int32")
        return VTK_TYPE_INT32;
    if (type == "Int64")
        return VTK_TYPE_INT64;
    if (type == "UInt64")
        return VTK_TYPE_UINT64;
    if (type == "UInt32")
        return VTK_TYPE_UINT32;
    if (type == "UInt8")
        return VTK_TYPE_UINT8;
    throw std::invalid_argument("VTK module: unknown array type '" + type + "'");
}

/// `values` as a VTK array of `tuples` tuples, without a copy (VTK never frees or writes it).
vtkSmartPointer<vtkDataArray> wrap(ArraySpec const& spec, void const* values, std::size_t tuples) {
    vtkSmartPointer<vtkDataArray> a;
    a.TakeReference(vtkDataArray::CreateDataArray(vtkTypeOf(spec.type)));
    a->SetName(spec.name.c_str());
    a->SetNumberOfComponents(spec.components);
    // save = 1: the caller owns the memory; VTK's writers take a non-const pointer but read.
    a->SetVoidArray(const_cast<void*>(values), // NOLINT(cppcoreguidelines-pro-type-const-cast)
                    static_cast<vtkIdType>(tuples) * spec.components, 1);
    return a;
}

void addColumns(vtkFieldData* to, std::vector<Column> const& columns, std::size_t tuples) {
    for (Column const& c : columns)
        to->AddArray(wrap(c.spec, c.values, tuples));
}

/// Raw appended binary (smaller and faster than base64) with 64-bit headers (pieces over
/// 4 GiB; the .pvtu and .vtm name that header type).
bool write(vtkXMLWriter* writer, std::string const& path, vtkDataObject* data) {
    writer->SetFileName(path.c_str());
    writer->SetInputData(data);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    writer->SetHeaderTypeToUInt64();
    // Write() reports success even when the file cannot be opened (a directory in its place,
    // no permission, a full disk); the error code says so.
    return writer->Write() == 1 && writer->GetErrorCode() == vtkErrorCode::NoError;
}

class VtkModule final : public Module {
public:
    bool writeVertices(std::string const& path, std::size_t count, double const* xyz,
                       std::vector<Column> const& pointData) override {
        vtkNew<vtkPoints> points;
        points->SetData(wrap({"Points", "Float64", 3}, xyz, count));
        vtkNew<vtkUnstructuredGrid> grid;
        grid->SetPoints(points);
        auto const n = static_cast<vtkIdType>(count);
        grid->Allocate(n);
        for (vtkIdType k = 0; k < n; ++k)
            grid->InsertNextCell(VTK_VERTEX, 1, &k);
        addColumns(grid->GetPointData(), pointData, count);
        vtkNew<vtkXMLUnstructuredGridWriter> writer;
        return write(writer, path, grid);
    }

    bool writeBoxes(std::string const& path, std::size_t count, double const* bounds,
                    std::vector<Column> const& cellData) override {
        // VTK_HEXAHEDRON order: the lower face counter-clockwise, then the upper face.
        constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                       {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
        vtkNew<vtkPoints> points;
        points->SetDataTypeToDouble();
        vtkNew<vtkUnstructuredGrid> grid;
        grid->Allocate(static_cast<vtkIdType>(count));
        for (std::size_t b = 0; b < count; ++b) {
            double const* lo = bounds + 6 * b;
            double const* hi = lo + 3;
            vtkIdType corners[8];
            for (int c = 0; c < 8; ++c)
                corners[c] = points->InsertNextPoint(kCorner[c][0] ? hi[0] : lo[0],
                                                     kCorner[c][1] ? hi[1] : lo[1],
                                                     kCorner[c][2] ? hi[2] : lo[2]);
            grid->InsertNextCell(VTK_HEXAHEDRON, 8, corners);
        }
        grid->SetPoints(points);
        addColumns(grid->GetCellData(), cellData, count);
        vtkNew<vtkXMLUnstructuredGridWriter> writer;
        return write(writer, path, grid);
    }

    bool writePolygons(std::string const& path, std::size_t count, double const* xyz,
                       std::vector<std::int64_t> const& offsets,
                       std::vector<std::int64_t> const& connectivity,
                       std::vector<Column> const& pointData,
                       std::vector<Column> const& cellData) override {
        vtkNew<vtkPoints> points;
        points->SetDataTypeToDouble();
        if (count > 0)
            points->SetData(wrap({"Points", "Float64", 3}, xyz, count));
        vtkNew<vtkTypeInt64Array> offsetArray, connectivityArray;
        offsetArray->SetNumberOfValues(static_cast<vtkIdType>(offsets.size()));
        for (std::size_t k = 0; k < offsets.size(); ++k)
            offsetArray->SetValue(static_cast<vtkIdType>(k), offsets[k]);
        connectivityArray->SetNumberOfValues(static_cast<vtkIdType>(connectivity.size()));
        for (std::size_t k = 0; k < connectivity.size(); ++k)
            connectivityArray->SetValue(static_cast<vtkIdType>(k), connectivity[k]);
        vtkNew<vtkCellArray> polygons;
        polygons->SetData(offsetArray, connectivityArray);
        vtkNew<vtkPolyData> poly;
        poly->SetPoints(points);
        poly->SetPolys(polygons);
        if (count > 0)
            addColumns(poly->GetPointData(), pointData, count);
        if (offsets.size() > 1)
            addColumns(poly->GetCellData(), cellData, offsets.size() - 1);
        vtkNew<vtkXMLPolyDataWriter> writer;
        return write(writer, path, poly);
    }

    bool writeImage(std::string const& path, std::array<int, 3> cells, std::array<double, 3> origin,
                    std::array<double, 3> spacing, std::vector<Column> const& cellData) override {
        vtkNew<vtkImageData> image;
        image->SetDimensions(cells[0] + 1, cells[1] + 1, cells[2] + 1); // points per axis
        image->SetOrigin(origin.data());
        image->SetSpacing(spacing.data());
        addColumns(image->GetCellData(), cellData,
                   static_cast<std::size_t>(cells[0]) * cells[1] * cells[2]);
        vtkNew<vtkXMLImageDataWriter> writer;
        return write(writer, path, image);
    }

    std::string readCollection(std::string const& path, std::vector<SeriesEntry>& out) override {
        vtkNew<vtkXMLDataParser> parser;
        parser->SetFileName(path.c_str());
        if (!std::filesystem::is_regular_file(path) || parser->Parse() != 1)
            return "cannot read the VTK series '" + path + "'";
        vtkXMLDataElement* root = parser->GetRootElement();
        vtkXMLDataElement* collection =
            root ? root->FindNestedElementWithName("Collection") : nullptr;
        if (collection == nullptr)
            return "'" + path + "' is not a VTK collection (.pvd)";
        for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
            vtkXMLDataElement* set = collection->GetNestedElement(i);
            char const* file = set->GetAttribute("file");
            double time = 0.0;
            if (file == nullptr || set->GetScalarAttribute("timestep", time) == 0)
                return "'" + path + "': DataSet " + std::to_string(i) + " has no file or timestep";
            out.push_back({time, file});
        }
        return "";
    }
};

} // namespace

} // namespace regolith::io::vtkxml

extern "C" regolith::io::vtkxml::Module* regolith_vtk_module() {
    // VTK would print its own error text on every failing rank; Regolith reports the failure
    // once, naming the file.
    vtkObject::GlobalWarningDisplayOff();
    static regolith::io::vtkxml::VtkModule instance;
    return &instance;
}
