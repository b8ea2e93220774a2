// Grid fields in VTK (io/vtk): grid gravity's density, potential and acceleration
// written per block as image data and gathered in a multi-block .vtm per step, read back
// with VTK's own XML readers (vtkXMLMultiBlockDataReader for the .vtm with its pieces,
// vtkXMLImageDataReader for one piece, vtkXMLDataParser for the grid.pvd series): block
// count, array names and sizes, origins and spacing, every interior value bit for bit,
// density x cell volume summing to the deposited mass, and a negative potential; on 1 and 4
// ranks. A restarted series keeps or replaces the entry of its first step.
#include "domain/BlockForest.hpp"
#include "gravity/GridGravity.hpp"
#include "io/vtk/VtkOutput.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLMultiBlockDataReader.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

using namespace regolith;
using core::Vec3;
namespace fs = std::filesystem;

namespace {

constexpr int kCells = 4; ///< per block and axis

/// [0, 8]^3 in 2 x 2 x 2 blocks of 4^3 cells (cell size 1), free space.
domain::ForestSpec spec() {
    domain::ForestSpec s;
    s.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
    s.rootBlocks = {2, 2, 2};
    s.periodic = {false, false, false};
    s.cellsPerBlock = {kCells, kCells, kCells};
    return s;
}

/// The file attributes of a .pvd's DataSets.
std::vector<std::string> pvdFiles(std::string const& path) {
    vtkNew<vtkXMLDataParser> parser;
    parser->SetFileName(path.c_str());
    std::vector<std::string> out;
    if (parser->Parse() != 1)
        return out;
    vtkXMLDataElement* collection = parser->GetRootElement()->GetNestedElement(0);
    for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i)
        out.emplace_back(collection->GetNestedElement(i)->GetAttribute("file"));
    return out;
}

} // namespace

TEST(VtkGridOutput, BlocksFieldsAndSeriesReadBack) {
    core::Comm const world;
    domain::BlockForest const forest(world, spec());
    gravity::GridGravityOptions options;
    options.poisson.G = 1.0;
    gravity::GridGravity grid(world, forest, {kCells, kCells, kCells}, options);
    // Three grains, deposited by the rank that holds them (rank 0: any rank may deposit any
    // grain, MeshTransfer sends the mass where it belongs).
    std::vector<Vec3> position;
    std::vector<double> radius, mass;
    if (world.rank() == 0) {
        position = {Vec3(4.0, 4.0, 4.0), Vec3(2.3, 5.1, 3.7), Vec3(6.2, 1.9, 5.5)};
        radius = {0.5, 0.4, 0.3};
        mass = {3.0, 1.5, 0.25};
    }
    double const total = 4.75;
    grid.update({position, radius, mass});

    std::string const dir = fmt::format("vtk_grid_test_np{}", world.size());
    if (world.rank() == 0)
        fs::remove_all(dir);
    world.barrier();
    particles::LocalParticles const local(forest);
    io::VtkOutput out(world, io::VtkOptions{dir, false, false});
    out.write(0, 0.0, local, grid.fields());
    out.write(5, 0.5, local, grid.fields());
    world.barrier();

    auto const series = pvdFiles(out.gridSeriesPath());
    ASSERT_EQ(series, (std::vector<std::string>{"vtk/grid_00000000.vtm", "vtk/grid_00000005.vtm"}));
    vtkNew<vtkXMLMultiBlockDataReader> reader;
    reader->SetFileName((dir + "/" + series[1]).c_str());
    reader->Update();
    auto* blocks = vtkMultiBlockDataSet::SafeDownCast(reader->GetOutput());
    ASSERT_NE(blocks, nullptr);
    ASSERT_EQ(blocks->GetNumberOfBlocks(), 8U);
    double mass0 = 0.0;
    double potentialMax = -1e300;
    std::set<std::array<double, 3>> origins;
    for (unsigned b = 0; b < 8; ++b) {
        auto* image = vtkImageData::SafeDownCast(blocks->GetBlock(b));
        ASSERT_NE(image, nullptr) << "block " << b;
        int dims[3];
        image->GetDimensions(dims);
        EXPECT_EQ(dims[0], kCells + 1); // points; ghost layers excluded
        EXPECT_EQ(dims[2], kCells + 1);
        EXPECT_EQ(image->GetNumberOfCells(), kCells * kCells * kCells);
        double spacing[3];
        image->GetSpacing(spacing);
        EXPECT_EQ(spacing[1], 1.0);
        double origin[3];
        image->GetOrigin(origin);
        origins.insert({origin[0], origin[1], origin[2]});
        vtkCellData* cd = image->GetCellData();
        ASSERT_NE(cd->GetArray("density"), nullptr);
        ASSERT_NE(cd->GetArray("potential"), nullptr);
        ASSERT_NE(cd->GetArray("acceleration"), nullptr);
        EXPECT_EQ(cd->GetArray("acceleration")->GetNumberOfComponents(), 3);
        EXPECT_EQ(cd->GetArray("density")->GetNumberOfTuples(), kCells * kCells * kCells);
        for (vtkIdType c = 0; c < image->GetNumberOfCells(); ++c) {
            mass0 += cd->GetArray("density")->GetTuple1(c) * spacing[0] * spacing[1] * spacing[2];
            potentialMax = std::max(potentialMax, cd->GetArray("potential")->GetTuple1(c));
        }
        EXPECT_STREQ(blocks->GetMetaData(b)->Get(vtkCompositeDataSet::NAME()),
                     fmt::format("block {}", b).c_str());
    }
    EXPECT_NEAR(mass0, total, 1e-12 * total); // every block once, no ghost cell counted
    EXPECT_LT(potentialMax, 0.0);             // attraction everywhere in free space
    EXPECT_EQ(origins.size(), 8U);
    EXPECT_TRUE(origins.count({4.0, 0.0, 4.0}) == 1);

    // Every local block's piece, read alone, holds exactly the field's interior cells.
    gravity::GridFieldsView const fields = grid.fields();
    gravity::CellField const* const densityField = fields.find("density");
    gravity::CellField const* const accelerationField = fields.find("acceleration");
    ASSERT_TRUE(densityField != nullptr && accelerationField != nullptr);
    for (std::size_t b = 0; b < forest.blocks().size(); ++b) {
        std::string const piece =
            fmt::format("{}/vtk/grid_00000005_b{:06d}.vti", dir, forest.blocks()[b].curveIndex);
        vtkNew<vtkXMLImageDataReader> one;
        one->SetFileName(piece.c_str());
        one->Update();
        vtkImageData* image = one->GetOutput();
        ASSERT_EQ(image->GetNumberOfCells(), kCells * kCells * kCells) << piece;
        double origin[3];
        image->GetOrigin(origin);
        EXPECT_EQ(origin[0], forest.blocks()[b].aabb.min.x());
        vtkDataArray* density = image->GetCellData()->GetArray("density");
        vtkDataArray* g = image->GetCellData()->GetArray("acceleration");
        int mismatches = 0;
        vtkIdType c = 0;
        for (int k = 0; k < kCells; ++k)
            for (int j = 0; j < kCells; ++j)
                for (int i = 0; i < kCells; ++i, ++c) {
                    mismatches += density->GetTuple1(c) != densityField->at(b, i, j, k);
                    for (int a = 0; a < 3; ++a)
                        mismatches += g->GetComponent(c, a) != accelerationField->at(b, i, j, k, a);
                }
        EXPECT_EQ(mismatches, 0) << piece;
    }
    world.barrier();

    // A restart from time 0.5 keeps the grid entries up to it (it has no grid to write at
    // its first step); one that writes the grid at 0.5 again replaces that entry.
    std::vector<std::string> const continued{"vtk/grid_00000000.vtm", "vtk/grid_00000005.vtm",
                                             "vtk/grid_00000008.vtm"};
    for (bool rewrite : {false, true}) {
        io::VtkOptions again{dir, false, false};
        again.keepEntriesBefore = 0.5;
        io::VtkOutput resumed(world, again);
        if (rewrite)
            resumed.write(5, 0.5, local, grid.fields());
        else
            resumed.write(5, 0.5, local); // no grid yet
        resumed.write(8, 0.8, local, grid.fields());
        world.barrier();
        EXPECT_EQ(pvdFiles(resumed.gridSeriesPath()), continued) << "rewrite " << rewrite;
        world.barrier();
    }

    // A fresh run into the same directory keeps the grid series only if it writes a grid: one
    // that writes none removes it (else it would pass for this run's).
    for (bool writesGrid : {true, false}) {
        io::VtkOptions fresh{dir, false, false};
        fresh.writesGrid = writesGrid;
        io::VtkOutput again(world, fresh);
        world.barrier();
        EXPECT_EQ(fs::exists(again.gridSeriesPath()), writesGrid);
        world.barrier();
    }
}
