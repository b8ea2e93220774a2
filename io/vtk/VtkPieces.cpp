#include "io/vtk/VtkPieces.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTypeInt64Array.h>
#include <vtkTypeUInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <array>

namespace regolith::io::detail {

std::vector<ArraySpec> particleArrays(bool shadows) {
    std::vector<ArraySpec> a{
        {"uid", "UInt64", 1},       {"radius", "Float64", 1},           {"mass", "Float64", 1},
        {"velocity", "Float64", 3}, {"angular_velocity", "Float64", 3}, {"force", "Float64", 3},
        {"owner_rank", "Int32", 1}};
    if (shadows)
        a.push_back({"shadow", "UInt8", 1});
    return a;
}

std::vector<ArraySpec> blockArrays() {
    return {{"block_id", "UInt64", 1},
            {"owner_rank", "Int32", 1},
            {"level", "Int32", 1},
            {"grains", "Int64", 1}};
}

namespace {

template <class Array>
vtkNew<Array> makeArray(char const* name, int components) {
    vtkNew<Array> a;
    a->SetName(name);
    a->SetNumberOfComponents(components);
    return a;
}

void write(std::string const& path, vtkUnstructuredGrid* grid) {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(grid);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff(); // raw binary: smaller and faster than base64
    writer->SetHeaderTypeToUInt64(); // pieces over 4 GiB; matches the .pvtu header_type
    if (writer->Write() != 1)
        throw core::Error(fmt::format("cannot write VTK file '{}'", path));
}

} // namespace

void writeParticlePiece(std::string const& path, particles::LocalParticles const& local,
                        bool shadows) {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    auto uid = makeArray<vtkTypeUInt64Array>("uid", 1);
    auto radius = makeArray<vtkDoubleArray>("radius", 1);
    auto mass = makeArray<vtkDoubleArray>("mass", 1);
    auto velocity = makeArray<vtkDoubleArray>("velocity", 3);
    auto omega = makeArray<vtkDoubleArray>("angular_velocity", 3);
    auto force = makeArray<vtkDoubleArray>("force", 3);
    auto owner = makeArray<vtkIntArray>("owner_rank", 1);
    auto shadow = makeArray<vtkUnsignedCharArray>("shadow", 1);
    for (particles::BlockParticles const& bp : local.blocks()) {
        particles::ParticleStorage const& ps = bp.particles;
        ps.forEach([&](std::size_t i) {
            bool const isShadow = ps.flags(i).isShadow();
            if (isShadow && !shadows)
                return;
            points->InsertNextPoint(ps.position(i).data());
            uid->InsertNextValue(ps.uid(i));
            radius->InsertNextValue(ps.radius(i));
            mass->InsertNextValue(ps.mass(i));
            velocity->InsertNextTuple(ps.velocity(i).data());
            omega->InsertNextTuple(ps.angularVelocity(i).data());
            force->InsertNextTuple(ps.force(i).data());
            owner->InsertNextValue(ps.owner(i).rank);
            shadow->InsertNextValue(isShadow ? 1 : 0);
        });
    }
    vtkNew<vtkUnstructuredGrid> grid;
    grid->SetPoints(points);
    vtkIdType const n = points->GetNumberOfPoints();
    grid->Allocate(n);
    for (vtkIdType k = 0; k < n; ++k)
        grid->InsertNextCell(VTK_VERTEX, 1, &k);
    vtkPointData* pd = grid->GetPointData();
    for (vtkDataArray* a :
         std::array<vtkDataArray*, 7>{uid, radius, mass, velocity, omega, force, owner})
        pd->AddArray(a);
    if (shadows)
        pd->AddArray(shadow);
    write(path, grid);
}

void writeBlockPiece(std::string const& path, particles::LocalParticles const& local) {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    auto id = makeArray<vtkTypeUInt64Array>("block_id", 1);
    auto owner = makeArray<vtkIntArray>("owner_rank", 1);
    auto level = makeArray<vtkIntArray>("level", 1);
    auto grains = makeArray<vtkTypeInt64Array>("grains", 1);
    vtkNew<vtkUnstructuredGrid> grid;
    grid->Allocate(static_cast<vtkIdType>(local.blocks().size()));
    for (particles::BlockParticles const& bp : local.blocks()) {
        core::AABB const& box = bp.block->aabb;
        std::array<vtkIdType, 8> corners{};
        // VTK_HEXAHEDRON order: the lower face counter-clockwise, then the upper face.
        constexpr std::array<std::array<int, 3>, 8> kCorner{{{0, 0, 0},
                                                             {1, 0, 0},
                                                             {1, 1, 0},
                                                             {0, 1, 0},
                                                             {0, 0, 1},
                                                             {1, 0, 1},
                                                             {1, 1, 1},
                                                             {0, 1, 1}}};
        for (std::size_t c = 0; c < 8; ++c) {
            auto const& k = kCorner[c];
            corners[c] = points->InsertNextPoint(k[0] ? box.max.x() : box.min.x(),
                                                 k[1] ? box.max.y() : box.min.y(),
                                                 k[2] ? box.max.z() : box.min.z());
        }
        grid->InsertNextCell(VTK_HEXAHEDRON, 8, corners.data());
        id->InsertNextValue(bp.block->id.raw());
        owner->InsertNextValue(bp.block->owner);
        level->InsertNextValue(bp.block->level);
        grains->InsertNextValue(static_cast<vtkTypeInt64>(bp.particles.countMasters()));
    }
    grid->SetPoints(points);
    vtkCellData* cd = grid->GetCellData();
    for (vtkDataArray* a : std::array<vtkDataArray*, 4>{id, owner, level, grains})
        cd->AddArray(a);
    write(path, grid);
}

namespace {

std::string declare(std::vector<ArraySpec> const& arrays) {
    std::string out;
    for (ArraySpec const& a : arrays)
        out +=
            fmt::format("      <PDataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n",
                        a.type, a.name, a.components);
    return out;
}

} // namespace

std::string pvtuText(std::vector<ArraySpec> const& pointArrays,
                     std::vector<ArraySpec> const& cellArrays,
                     std::vector<std::string> const& pieces) {
    std::string out = "<?xml version=\"1.0\"?>\n"
                      "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
                      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                      "  <PUnstructuredGrid GhostLevel=\"0\">\n";
    out += "    <PPointData>\n" + declare(pointArrays) + "    </PPointData>\n";
    out += "    <PCellData>\n" + declare(cellArrays) + "    </PCellData>\n";
    out += "    <PPoints>\n      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
           "    </PPoints>\n";
    for (std::string const& p : pieces)
        out += fmt::format("    <Piece Source=\"{}\"/>\n", p);
    out += "  </PUnstructuredGrid>\n</VTKFile>\n";
    return out;
}

} // namespace regolith::io::detail
