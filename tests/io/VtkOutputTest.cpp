// VTK output for ParaView (io/vtk): every file a run writes is read back with VTK's own XML
// readers (vtkXMLPUnstructuredGridReader for the .pvtu with its pieces, vtkXMLDataParser for
// the .pvd series), and its counts, array names and value ranges checked; on 1 and 4 ranks,
// with and without shadows.
#include "io/vtk/VtkOutput.hpp"

#include "core/Error.hpp"
#include "domain/BlockForest.hpp"
#include "io/vtk/WallPieces.hpp"
#include "particles/sync/ParticleSync.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLPolyDataReader.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace regolith;
using core::Vec3;
namespace fs = std::filesystem;

namespace {

constexpr int kGrains = 125;

domain::ForestSpec spec() {
    domain::ForestSpec s;
    s.domain = core::AABB{Vec3::Zero(), Vec3::Constant(10.0)};
    s.rootBlocks = {2, 2, 2};
    s.periodic = {true, true, false};
    return s;
}

/// 5 x 5 x 5 grains of radius 0.6 at spacing 2 starting at 1: those at 5 touch the block
/// faces at x, y, z = 5 and get shadows; uids 10, 11, ...
void fill(particles::LocalParticles& local) {
    for (int k = 0; k < kGrains; ++k) {
        particles::ParticleInit p;
        p.uid = static_cast<particles::Uid>(10 + k);
        p.position = Vec3(1.0 + 2.0 * (k % 5), 1.0 + 2.0 * (k / 5 % 5), 1.0 + 2.0 * (k / 25));
        p.velocity = Vec3(0.125 * (k % 7), -0.5, 0.0);
        p.radius = 0.6;
        p.mass = 2.0;
        (void)local.addMaster(p); // false: another rank's grain
    }
}

vtkSmartPointer<vtkUnstructuredGrid> readPvtu(std::string const& path) {
    vtkNew<vtkXMLPUnstructuredGridReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
    return grid;
}

std::array<double, 2> range(vtkDataArray* a, int component = 0) {
    std::array<double, 2> r{};
    a->GetRange(r.data(), component);
    return r;
}

/// The `file` attributes of the DataSets of a .pvd, and their timesteps.
std::vector<std::pair<double, std::string>> readPvd(std::string const& path) {
    vtkNew<vtkXMLDataParser> parser;
    parser->SetFileName(path.c_str());
    std::vector<std::pair<double, std::string>> out;
    if (parser->Parse() != 1)
        return out;
    vtkXMLDataElement* collection = parser->GetRootElement()->GetNestedElement(0);
    for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement* set = collection->GetNestedElement(i);
        out.emplace_back(std::stod(set->GetAttribute("timestep")), set->GetAttribute("file"));
    }
    return out;
}

} // namespace

/// The particles on one subdomain per block, or on each rank's blocks merged: the same grains,
/// and blocks.pvd the forest's blocks either way.
class VtkOutputOn : public ::testing::TestWithParam<domain::Subdomains> {};

TEST_P(VtkOutputOn, ParticlesBlocksAndSeriesReadBack) {
    core::Comm const world;
    domain::BlockForest const forest(world, spec(), {}, GetParam());
    particles::LocalParticles local(forest);
    fill(local);
    particles::ParticleSync sync(world, forest, particles::SyncConfig{});
    sync.syncUntilConverged(local);
    long long const copies =
        world.allReduce(static_cast<long long>(local.countCopies()), core::ReduceOp::Sum);
    if (GetParam() == domain::Subdomains::RankBoxes && world.size() == 1) {
        EXPECT_EQ(copies, kGrains); // one subdomain, the whole open domain: no shadows
    } else {
        ASSERT_GT(copies, kGrains); // the grains on the faces have shadows
    }

    for (bool shadows : {false, true}) {
        std::string const dir =
            fmt::format("vtk_test_np{}_{}_{}", world.size(), shadows, static_cast<int>(GetParam()));
        if (world.rank() == 0)
            fs::remove_all(dir);
        world.barrier();
        io::VtkOutput out(world, io::VtkOptions{dir, shadows, true});
        out.write(0, 0.0, local);
        out.write(10, 0.25, local);
        world.barrier();

        auto const series = readPvd(out.particleSeriesPath());
        ASSERT_EQ(series.size(), 2U);
        EXPECT_EQ(series[1].first, 0.25);
        EXPECT_EQ(series[1].second, "vtk/particles_00000010.pvtu");
        auto const grid = readPvtu(dir + "/" + series[1].second);
        vtkPointData* pd = grid->GetPointData();
        EXPECT_EQ(grid->GetNumberOfPoints(), shadows ? copies : kGrains);
        EXPECT_EQ(grid->GetNumberOfCells(), grid->GetNumberOfPoints());
        std::array<double, 6> pointBounds{};
        grid->GetBounds(pointBounds.data()); // the grains' centres: 1, 3, ..., 9 on each axis
        EXPECT_EQ(pointBounds, (std::array<double, 6>{1.0, 9.0, 1.0, 9.0, 1.0, 9.0}));
        for (char const* name :
             {"uid", "radius", "mass", "velocity", "angular_velocity", "force", "owner_rank"})
            ASSERT_NE(pd->GetArray(name), nullptr) << name;
        EXPECT_EQ(pd->GetArray("shadow") != nullptr, shadows);
        EXPECT_EQ(range(pd->GetArray("uid")), (std::array<double, 2>{10.0, 10.0 + kGrains - 1}));
        EXPECT_EQ(range(pd->GetArray("radius")), (std::array<double, 2>{0.6, 0.6}));
        EXPECT_EQ(range(pd->GetArray("velocity"), 1), (std::array<double, 2>{-0.5, -0.5}));
        EXPECT_EQ(range(pd->GetArray("velocity"), 0), (std::array<double, 2>{0.0, 0.75}));
        EXPECT_EQ(pd->GetArray("velocity")->GetNumberOfComponents(), 3);
        auto const owners = range(pd->GetArray("owner_rank"));
        EXPECT_GE(owners[0], 0.0);
        EXPECT_LE(owners[1], world.size() - 1.0);
        if (shadows) {
            EXPECT_EQ(range(pd->GetArray("shadow")),
                      (std::array<double, 2>{0.0, copies > kGrains ? 1.0 : 0.0}));
        }

        auto const blockSeries = readPvd(out.blockSeriesPath());
        ASSERT_EQ(blockSeries.size(), 2U);
        auto const blocks = readPvtu(dir + "/" + blockSeries[0].second);
        EXPECT_EQ(blocks->GetNumberOfCells(), 8);
        EXPECT_EQ(blocks->GetNumberOfPoints(), 64);
        vtkCellData* cd = blocks->GetCellData();
        double total = 0.0;
        std::map<double, double> grainsPerBlock; // by block id
        for (vtkIdType c = 0; c < 8; ++c) {
            total += cd->GetArray("grains")->GetTuple1(c);
            grainsPerBlock[cd->GetArray("block_id")->GetTuple1(c)] =
                cd->GetArray("grains")->GetTuple1(c);
        }
        EXPECT_EQ(total, kGrains);
        EXPECT_EQ(grainsPerBlock.size(), 8U); // every block once, merged or not
        // fill's grains per block: centres 1, 3 below the faces at 5, and 5, 7, 9 above.
        std::multiset<double> counts;
        for (auto const& [id, n] : grainsPerBlock)
            counts.insert(n);
        EXPECT_EQ(counts, (std::multiset<double>{8, 12, 12, 12, 18, 18, 18, 27}));
        EXPECT_EQ(range(cd->GetArray("level")), (std::array<double, 2>{0.0, 0.0}));
        EXPECT_EQ(range(cd->GetArray("owner_rank"))[1], std::min(world.size(), 8) - 1.0);
        EXPECT_NE(cd->GetArray("block_id"), nullptr);
        double bounds[6];
        blocks->GetBounds(bounds);
        EXPECT_EQ(bounds[1], 10.0);
        world.barrier(); // nobody removes a directory another rank still reads
    }
}

INSTANTIATE_TEST_SUITE_P(Subdomains, VtkOutputOn,
                         ::testing::Values(domain::Subdomains::Blocks,
                                           domain::Subdomains::RankBoxes),
                         [](auto const& p) {
                             return p.param == domain::Subdomains::Blocks ? "Blocks" : "Merged";
                         });

TEST(VtkOutput, UnwritableDirectoryIsRefused) {
    core::Comm const world;
    try {
        io::VtkOutput out(world, io::VtkOptions{"/proc/no_vtk_here", false, true});
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find("output.dir = \"/proc/no_vtk_here\": cannot create"),
                  std::string::npos)
            << e.what();
    }
}

/// A piece that cannot be written (here a directory in its place, on the last rank; a full
/// disk or a missing permission alike) stops every rank with the file's name, and no index
/// names it: VTK's writer reports success then, only its error code tells.
TEST(VtkOutput, UnwritablePieceIsAnErrorOnEveryRank) {
    core::Comm const world;
    domain::BlockForest const forest(world, spec());
    particles::LocalParticles local(forest);
    fill(local);
    std::string const dir = fmt::format("vtk_unwritable_np{}", world.size());
    std::string const blocked =
        fmt::format("{}/vtk/particles_00000010_r{:04d}.vtu", dir, world.size() - 1);
    if (world.rank() == 0) {
        fs::remove_all(dir);
        fs::create_directories(blocked);
    }
    world.barrier();
    io::VtkOutput out(world, io::VtkOptions{dir, false, true});
    try {
        out.write(10, 0.25, local);
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find("cannot write '" + blocked + "'"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(fs::exists(dir + "/vtk/particles_00000010.pvtu"));
    world.barrier();
    // An index that cannot be renamed into place leaves no temporary behind.
    if (world.rank() == 0) {
        fs::remove_all(blocked);
        fs::create_directories(dir + "/particles.pvd/x");
    }
    world.barrier();
    EXPECT_THROW(out.write(20, 0.5, local), core::InputError);
    for (auto const& entry : fs::directory_iterator(dir))
        EXPECT_FALSE(entry.path().filename().string().starts_with("particles.pvd.tmp"))
            << entry.path();
    world.barrier();
    if (world.rank() == 0)
        fs::remove_all(dir);
}

namespace {

std::string contentOf(std::string const& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

} // namespace

/// A piece or series name that is a symbolic link, and a leftover temporary that is one: the
/// link under the output's name is replaced, and nothing is written through a link.
TEST(VtkOutput, LinksUnderItsNamesAreReplacedNotWrittenThrough) {
    core::Comm const world;
    domain::BlockForest const forest(world, spec());
    particles::LocalParticles local(forest);
    fill(local);
    std::string const dir = fmt::format("vtk_links_np{}", world.size());
    std::string const victim = dir + "/victim.txt";
    // Rank 0 writes the series: its process id names the temporary it would take first.
    long const pid = world.allReduce(world.rank() == 0 ? static_cast<long>(::getpid()) : 0L,
                                     core::ReduceOp::Sum);
    std::string const leftover = fmt::format("{}/blocks.pvd.tmp{}", dir, pid);
    if (world.rank() == 0) {
        fs::remove_all(dir);
        fs::create_directories(dir + "/vtk");
        std::ofstream(victim) << "keep";
        for (int r = 0; r < world.size(); ++r)
            fs::create_symlink("../victim.txt",
                               fmt::format("{}/vtk/particles_00000010_r{:04d}.vtu", dir, r));
        fs::create_symlink("victim.txt", leftover);
    }
    world.barrier();
    io::VtkOutput out(world, io::VtkOptions{dir, false, true});
    out.write(10, 0.25, local);
    world.barrier();
    EXPECT_EQ(contentOf(victim), "keep");
    std::string const piece =
        fmt::format("{}/vtk/particles_00000010_r{:04d}.vtu", dir, world.rank());
    EXPECT_FALSE(fs::is_symlink(piece));
    EXPECT_TRUE(fs::is_regular_file(piece));
    EXPECT_EQ(readPvd(dir + "/particles.pvd").size(), 1U);
    EXPECT_TRUE(fs::is_symlink(leftover)); // not ours to remove
    EXPECT_EQ(readPvd(dir + "/blocks.pvd").size(), 1U);
    world.barrier();
    if (world.rank() == 0)
        fs::remove_all(dir);
}

/// A file under a series' name that this program did not write is the user's: not removed
/// (grid.pvd, which a run without grid gravity removes when it is an earlier run's series),
/// not replaced (a series this run writes: refused before anything is written).
TEST(VtkOutput, OnlyItsOwnSeriesAreRemovedOrReplaced) {
    core::Comm const world;
    std::string const dir = fmt::format("vtk_users_files_np{}", world.size());
    std::string const notes = "my own grid notes\n";
    if (world.rank() == 0) {
        fs::remove_all(dir);
        fs::create_directories(dir);
        std::ofstream(dir + "/grid.pvd") << notes;
    }
    world.barrier();
    {
        io::VtkOutput const fresh(world, io::VtkOptions{dir, false, true});
        world.barrier();
        EXPECT_EQ(contentOf(dir + "/grid.pvd"), notes);
    }
    std::string const collection =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
        "  <Collection>\n    <DataSet timestep=\"0\" file=\"mine/run1.vtu\"/>\n"
        "  </Collection>\n</VTKFile>\n";
    if (world.rank() == 0)
        std::ofstream(dir + "/particles.pvd") << collection;
    world.barrier();
    try {
        io::VtkOutput const refused(world, io::VtkOptions{dir, false, true});
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find("holds 'particles.pvd', which is not a particles "
                                             "series this program writes"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_EQ(contentOf(dir + "/particles.pvd"), collection);
    world.barrier();
    if (world.rank() == 0)
        fs::remove_all(dir);
}

// Walls as polygons: a plane cut to the box, a rectangle, a disc and a turning drum (48 sides
// along the box), with the wall material's velocity; written by rank 0 and read back.
TEST(VtkOutput, WallsReadBack) {
    core::Comm const world;
    particles::WallList walls;
    walls.add(Vec3(0, 0, 2), Vec3(0, 0, 1)); // cuts the box [0, 10]^3 in a square
    particles::Wall plate;
    plate.geometry.shape = particles::WallShape::Rectangle;
    plate.geometry.point = Vec3(5, 5, 5);
    plate.geometry.normal = Vec3(1, 0, 0);
    plate.geometry.edge = Vec3(0, 1, 0);
    plate.geometry.halfSize[0] = 1.0;
    plate.geometry.halfSize[1] = 2.0;
    walls.add(plate);
    particles::Wall disc = plate;
    disc.geometry.shape = particles::WallShape::Disc;
    disc.geometry.radius = 1.5;
    walls.add(disc);
    particles::Wall drum;
    drum.geometry.shape = particles::WallShape::Cylinder;
    drum.geometry.point = Vec3(5, 5, 0);
    drum.geometry.normal = Vec3(0, 0, 1);
    drum.geometry.radius = 4.0;
    drum.motion.centre = drum.geometry.point;
    drum.motion.angularVelocity = Vec3(0, 0, 0.5);
    walls.add(drum);
    walls.moveTo(1.0);
    core::AABB const box{Vec3::Zero(), Vec3::Constant(10.0)};
    io::detail::WallMesh const mesh = io::detail::wallMesh(walls, box);
    ASSERT_EQ(mesh.wall.size(), 3u + io::detail::kCircleSides);
    EXPECT_EQ(mesh.offsets[1], 4);                                          // the plane's square
    EXPECT_EQ(mesh.offsets[3] - mesh.offsets[2], io::detail::kCircleSides); // the disc
    for (std::int64_t k = mesh.offsets[0]; k < mesh.offsets[1]; ++k)
        EXPECT_EQ(
            mesh.xyz[3 * static_cast<std::size_t>(mesh.connectivity[static_cast<std::size_t>(k)]) +
                     2],
            2.0);

    std::string const dir = fmt::format("vtk_walls_np{}", world.size());
    io::VtkOptions options{dir, false, false};
    options.writesWalls = true;
    io::VtkOutput out(world, options);
    out.writeWalls(7, 0.25, walls, box);
    world.barrier();
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName((fs::path(dir) / "vtk" / "walls_00000007.vtp").c_str());
    reader->Update();
    vtkPolyData* poly = reader->GetOutput();
    ASSERT_EQ(poly->GetNumberOfPolys(), 3 + io::detail::kCircleSides);
    vtkDataArray* velocity = poly->GetPointData()->GetArray("velocity");
    ASSERT_NE(velocity, nullptr);
    double range[2];
    velocity->GetRange(range, -1); // the magnitude: 0 on the fixed walls, 0.5 x 4 on the drum
    EXPECT_DOUBLE_EQ(range[0], 0.0);
    EXPECT_NEAR(range[1], 2.0, 1e-12);
    ASSERT_NE(poly->GetCellData()->GetArray("wall"), nullptr);
    std::ifstream pvd(fs::path(dir) / "walls.pvd");
    std::stringstream text;
    text << pvd.rdbuf();
    EXPECT_NE(
        text.str().find("timestep=\"0.25\" group=\"\" part=\"0\" file=\"vtk/walls_00000007.vtp\""),
        std::string::npos)
        << text.str();
}
