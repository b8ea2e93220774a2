// The table of built-in per-grain quantities (particles/storage/GrainQuantities.hpp) drives every
// output: for each entry, a checkpoint has its dataset with the entry's units and description and
// gives its value back bit for bit, a VTK particle piece has its array exactly when the entry
// says so, the dump has its columns exactly when the entry says so, and a shadow made through
// the synchronisation's full-state record carries the value of every entry the storage keeps.
#include "apps/common/StateDump.hpp"
#include "core/mpi/Comm.hpp"
#include "domain/BlockForest.hpp"
#include "io/checkpoint/CheckpointReader.hpp"
#include "io/checkpoint/CheckpointWriter.hpp"
#include "io/checkpoint/GrainState.hpp"
#include "io/vtk/VtkPieces.hpp"
#include "particles/storage/GrainQuantities.hpp"
#include "particles/sync/BlockParticles.hpp"
#include "particles/sync/SyncMessages.hpp"
#include "tests/io/DatasetText.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>
#include <unistd.h>

using namespace regolith;

namespace {

using particles::GrainLayoutOf;
using particles::kGrainQuantity;

template <std::size_t K>
using ElementsOf = std::array<typename GrainLayoutOf<K>::Element, kGrainQuantity<K>.components>;

/// A value of entry K no other entry has, component by component (a fixed grain for flags).
template <std::size_t K>
ElementsOf<K> distinctElements(std::uint64_t salt) {
    ElementsOf<K> e{};
    for (std::size_t c = 0; c < e.size(); ++c) {
        using Element = typename GrainLayoutOf<K>::Element;
        if constexpr (std::is_same_v<Element, std::uint8_t>)
            e[c] = static_cast<Element>(particles::Flags(particles::Flag::Fixed).bits());
        else
            e[c] = static_cast<Element>(1000 * salt + 10 * K + c) + Element(1) / Element(4);
    }
    return e;
}

/// A grain whose every entry holds distinctElements (io::GrainState holds every entry).
io::GrainState distinctRow(std::uint64_t salt) {
    io::GrainState r;
    particles::forEachGrainQuantity([&](auto k) {
        ElementsOf<k.value> const e = distinctElements<k.value>(salt);
        r.*kGrainQuantity<k.value>.row = GrainLayoutOf<k.value>::get(e.data());
    });
    return r;
}

/// Entry K's value in `row` (a row type holding entry K) as its column elements.
template <std::size_t K, class Row>
ElementsOf<K> elementsOf(Row const& row) {
    ElementsOf<K> e{};
    GrainLayoutOf<K>::put(row.*kGrainQuantity<K>.row, e.data());
    return e;
}

std::string tempPath(core::Comm const& comm, std::string const& name) {
    long long const pid = comm.allReduce(static_cast<long long>(::getpid()), core::ReduceOp::Max);
    return (std::filesystem::temp_directory_path() / (std::to_string(pid) + "-" + name)).string();
}

/// The salt of distinctRow(salt) from the uid it gave.
std::uint64_t saltOf(particles::Uid uid) {
    return uid / 1000;
}

} // namespace

TEST(GrainQuantities, EveryEntryIsACheckpointColumnReadBackBitForBit) {
    core::Comm const world;
    io::GrainState const g = distinctRow(1 + static_cast<std::uint64_t>(world.rank()));
    std::string const path = tempPath(world, "grain-quantities.h5");
    io::CheckpointInfo info;
    info.dt = 0.01;
    (void)io::writeCheckpoint(world, path, info, std::vector<io::GrainState>{g});
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    EXPECT_EQ(world.allReduce(static_cast<int>(slice.grains.size()), core::ReduceOp::Sum),
              world.size());
    if (world.rank() == 0) {
        hid_t const file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
        ASSERT_GE(file, 0);
        particles::forEachGrainQuantity([&](auto k) {
            constexpr auto const& q = kGrainQuantity<k.value>;
            std::string const name(q.name);
            bool const written = particles::grainWrittenTo<k.value>(particles::kCheckpoint);
            EXPECT_EQ(H5Lexists(file, name.c_str(), H5P_DEFAULT) > 0, written) << name;
            if (written) {
                EXPECT_EQ(test::datasetText(path, name.c_str(), "units"), q.unit) << name;
                EXPECT_EQ(test::datasetText(path, name.c_str(), "description"), q.description)
                    << name;
            }
        });
        H5Fclose(file);
    }
    for (io::GrainState const& r : slice.grains) {
        io::GrainState const expected = distinctRow(saltOf(r.uid));
        particles::forEachGrainQuantity([&](auto k) {
            if constexpr (particles::grainWrittenTo<k.value>(particles::kCheckpoint)) {
                EXPECT_EQ(elementsOf<k.value>(r), elementsOf<k.value>(expected))
                    << kGrainQuantity<k.value>.name;
            }
        });
    }
    world.barrier();
    if (world.rank() == 0)
        std::filesystem::remove(path);
}

TEST(GrainQuantities, TheVtkPieceHasAnArrayPerEntryMarkedForIt) {
    core::Comm const world;
    domain::ForestSpec spec;
    spec.domain = core::AABB{core::Vec3::Zero(), core::Vec3::Constant(4.0)};
    spec.rootBlocks = {1, 1, 1};
    domain::BlockForest const forest(world, spec);
    particles::LocalParticles local(forest);
    particles::ParticleInit p;
    static_cast<particles::GrainRow&>(p) = distinctRow(1);
    p.position = core::Vec3::Constant(2.0);
    (void)local.addMaster(p);
    std::string const path = tempPath(world, std::to_string(world.rank()) + "-quantities.vtu");
    io::detail::writeParticlePiece(path, local, true);
    std::stringstream text;
    text << std::ifstream(path, std::ios::binary).rdbuf();
    std::filesystem::remove(path);
    std::vector<io::vtkxml::ArraySpec> const arrays = io::detail::particleArrays(true);
    particles::forEachGrainQuantity([&](auto k) {
        constexpr auto const& q = kGrainQuantity<k.value>;
        std::string const name(q.name);
        bool const written = particles::grainWrittenTo<k.value>(particles::kVtk);
        EXPECT_EQ(text.str().find("Name=\"" + name + "\"") != std::string::npos, written) << name;
        auto const array = std::find_if(arrays.begin(), arrays.end(),
                                        [&](auto const& a) { return a.name == name; });
        ASSERT_EQ(array != arrays.end(), written) << name;
        if (written) {
            EXPECT_EQ(array->components, static_cast<int>(q.components)) << name;
        }
    });
}

TEST(GrainQuantities, TheDumpHasTheColumnsOfEveryEntryMarkedForIt) {
    io::GrainState const all = distinctRow(7);
    apps::MasterRecord m;
    static_cast<particles::GrainRow&>(m) = all;
    std::string const csv = apps::dumpCsv(std::span(&m, 1));
    std::string const header = csv.substr(0, csv.find('\n'));
    std::string expected;
    particles::forEachGrainQuantity([&](auto k) {
        constexpr auto const& q = kGrainQuantity<k.value>;
        bool const dumped = particles::grainWrittenTo<k.value>(particles::kDump);
        EXPECT_EQ(!q.dumpColumns.empty(), dumped) << q.name;
        if (dumped) {
            if (!expected.empty())
                expected += ',';
            expected += q.dumpColumns;
            // The columns' count is the entry's components.
            EXPECT_EQ(static_cast<std::size_t>(
                          std::count(q.dumpColumns.begin(), q.dumpColumns.end(), ',') + 1),
                      q.components)
                << q.name;
            // Its first component's value is in the line (every value here is distinct).
            std::string const first =
                fmt::format("{:.17g}", static_cast<double>(elementsOf<k.value>(all)[0]));
            EXPECT_NE(csv.find(first), std::string::npos) << q.name << ": " << csv;
        }
    });
    EXPECT_EQ(header.substr(0, expected.size()), expected);
}

TEST(GrainQuantities, AShadowMadeByTheFullStateRecordCarriesEveryKeptEntry) {
    using namespace particles::sync_detail;
    particles::ParticleStorage master;
    particles::ParticleInit p;
    static_cast<particles::GrainRow&>(p) = distinctRow(3);
    std::size_t const i = master.add(p);
    core::Vec3 const shifted = p.position + core::Vec3(16.0, 0.0, 0.0); // a periodic image
    core::SendBuffer out;
    writeFull(out, master, i, shifted, particles::CopyImage{1, 0, 0}, {0, 5}, {});
    core::RecvBuffer in(std::vector<std::byte>(out.bytes().begin(), out.bytes().end()));
    particles::ParticleStorage shadows;
    std::size_t const k = addFull(shadows, readFull(in), false);
    EXPECT_TRUE(in.exhausted());
    particles::GrainRow expected = master.row(i);
    expected.position = shifted;
    expected.flags.set(particles::Flag::Shadow, true);
    particles::GrainRow const got = shadows.row(k);
    particles::forEachGrainQuantity([&](auto q) {
        if constexpr (kGrainQuantity<q.value>.storage != particles::GrainStorage::Elsewhere) {
            EXPECT_EQ(elementsOf<q.value>(got), elementsOf<q.value>(expected))
                << kGrainQuantity<q.value>.name;
            // Every entry's value is distinct from its default: the record did carry it.
            EXPECT_NE(elementsOf<q.value>(got), elementsOf<q.value>(particles::GrainRow{}))
                << kGrainQuantity<q.value>.name;
        }
    });
}
