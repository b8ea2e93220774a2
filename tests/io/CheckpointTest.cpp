// HDF5 checkpoints (io/checkpoint): every stored field of every master, contact history
// included, survives a write and a read bit for bit, also when a sub-communicator of another
// size reads what all ranks wrote; a truncated file, a flipped data byte and another format
// version are refused with one message on every rank and the file left as it was; rotation
// keeps the newest files.
#include "core/Error.hpp"
#include "domain/BlockForest.hpp"
#include "io/checkpoint/CheckpointReader.hpp"
#include "io/checkpoint/CheckpointSeries.hpp"
#include "io/checkpoint/CheckpointWriter.hpp"
#include "io/checkpoint/RestoreGrains.hpp"
#include "tests/io/DatasetText.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace regolith;
using core::Vec3;
namespace fs = std::filesystem;

namespace {

domain::ForestSpec spec() {
    domain::ForestSpec s;
    s.domain = core::AABB{Vec3::Zero(), Vec3::Constant(8.0)};
    s.rootBlocks = {2, 2, 2};
    s.periodic = {true, false, false};
    return s;
}

/// 64 grains on a lattice with values that use every bit of their fields, rank-independent;
/// every third grain has 1-3 history entries.
std::vector<io::GrainState> allGrains() {
    std::vector<io::GrainState> out;
    for (int k = 0; k < 64; ++k) {
        io::GrainState g;
        g.uid = static_cast<particles::Uid>(1000 + 7 * k);
        double const f = 1.0 + k / 3.0;
        g.position = Vec3(0.5 + (k % 4) * 2.0, 0.5 + (k / 4 % 4) * 2.0, 0.5 + (k / 16) * 2.0);
        g.velocity = Vec3(0.1 / f, -0.2 * f, 1e-17 * f);
        g.angularVelocity = Vec3(-0.0, 3.0 / f, 1.0 / 7.0);
        g.orientation = core::Quat(Eigen::AngleAxisd(0.1 * k, Vec3(1, 2, 3).normalized()));
        g.force = Vec3(f, -f / 3.0, 1e300);
        g.torque = Vec3(1e-300, -f, 2.0 / 3.0);
        g.radius = 0.4 + 1e-3 * k;
        g.mass = 4.0 * g.radius * g.radius * g.radius;
        g.type = static_cast<std::uint32_t>(k % 3);
        // Fixed on every fifth grain; the synchronisation class (SOS, and SOS spread by its
        // master alone) on others: every flag a master carries must survive a restart.
        particles::Flags flags;
        flags.set(particles::Flag::Fixed, k % 5 == 0);
        flags.set(particles::Flag::Spreads, k % 7 < 2);
        flags.set(particles::Flag::MasterReachesAll, k % 7 == 0);
        g.flags = flags;
        if (k % 3 == 0)
            for (int e = 0; e <= k % 3 + k % 2; ++e)
                g.history.push_back({g.uid + 1 + static_cast<particles::Uid>(e),
                                     Vec3(1e-3 * e, -f * 1e-4, 1.0 / 3.0), 41U});
        out.push_back(g);
    }
    return out;
}

/// This rank's share: the grains its blocks contain.
particles::LocalParticles fill(domain::BlockForest const& forest) {
    particles::LocalParticles local(forest);
    for (io::GrainState const& g : allGrains())
        if (forest.localBlockContaining(g.position) != nullptr) {
            local.addMaster(io::toParticleInit(g));
            for (particles::BlockParticles& bp : local.blocks())
                if (auto i = bp.particles.find(g.uid); i != particles::ParticleStorage::kNotFound)
                    io::restoreHistory(g, bp.particles, i);
        }
    return local;
}

std::vector<io::GrainState> sortedMasters(particles::LocalParticles const& local) {
    auto out = io::collectMasters(local);
    std::sort(out.begin(), out.end(), [](auto const& a, auto const& b) { return a.uid < b.uid; });
    return out;
}

/// Equal in every bit of every field (the hashes cover every stored field).
void expectSame(std::vector<io::GrainState> const& a, std::vector<io::GrainState> const& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].uid, b[i].uid);
        EXPECT_EQ(io::grainHash(a[i]), io::grainHash(b[i])) << "uid " << a[i].uid;
        EXPECT_EQ(a[i].history.size(), b[i].history.size());
    }
}

/// A file name per test and rank count (ctest may run the 1- and 4-rank tests together).
std::string fileName(core::Comm const& comm, std::string const& what) {
    return fmt::format("checkpoint_test_np{}_{}.h5", comm.size(), what);
}

io::CheckpointInfo info() {
    io::CheckpointInfo i;
    i.step = 20;
    i.time = 0.2;
    i.dt = 0.01;
    i.domain = spec().domain;
    i.periodic = spec().periodic;
    i.scene = "[domain]\nmin = [0,0,0]\n";
    i.stateChecksum = "0123456789abcdef";
    return i;
}

/// Whether a temporary of `path` ("<path>.tmp...") is in its directory.
bool hasTemporary(std::string const& path) {
    fs::path const dir = fs::absolute(path).parent_path();
    std::string const prefix = fs::path(path).filename().string() + ".tmp";
    for (auto const& entry : fs::directory_iterator(dir))
        if (entry.path().filename().string().starts_with(prefix))
            return true;
    return false;
}

/// Writes the checkpoint of `fill` to `path`. COLLECTIVE.
void writeSample(core::Comm const& comm, std::string const& path) {
    domain::BlockForest const forest(comm, spec());
    auto const local = fill(forest);
    auto const grains = io::collectMasters(local);
    io::CheckpointInfo i = info();
    std::uint64_t const bytes = io::writeCheckpoint(comm, path, i, grains);
    EXPECT_GT(bytes, 64U * 20U * 8U);
    EXPECT_EQ(i.grainCount, 64U);
    EXPECT_FALSE(hasTemporary(path));
}

/// The message readCheckpoint throws on every rank (or "" if it does not throw).
/// Overwrites the root attribute `name` of the file at `path` (rank 0 only).
template <class T>
void overwriteAttribute(std::string const& path, char const* name, hid_t type, T value) {
    hid_t const file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t const attr = H5Aopen(file, name, H5P_DEFAULT);
    H5Awrite(attr, type, &value);
    H5Aclose(attr);
    H5Fclose(file);
}

std::string readError(core::Comm const& comm, std::string const& path) {
    try {
        (void)io::readCheckpoint(comm, path);
    } catch (core::InputError const& e) {
        return e.what();
    }
    return "";
}

std::string fileBytes(std::string const& path) {
    std::string bytes(fs::file_size(path), '\0');
    std::ifstream(path, std::ios::binary)
        .read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return bytes;
}

} // namespace

TEST(Checkpoint, RoundTripIsBitwise) {
    core::Comm const world;
    std::string const path = fileName(world, "roundtrip");
    writeSample(world, path);
    domain::BlockForest const forest(world, spec());
    auto const expected = sortedMasters(fill(forest));
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    EXPECT_EQ(slice.info.step, 20);
    EXPECT_EQ(slice.info.time, 0.2);
    EXPECT_EQ(slice.info.scene, info().scene);
    EXPECT_EQ(slice.info.stateChecksum, info().stateChecksum);
    EXPECT_EQ(slice.info.historyCount, 33U); // 11 grains with one entry, 11 with two
    particles::LocalParticles restored(forest);
    io::restoreGrains(world, restored, slice.grains, "test");
    expectSame(expected, sortedMasters(restored));
    // Every flag byte as written, the synchronisation class included.
    std::vector<io::GrainState> const written = allGrains();
    for (io::GrainState const& g : sortedMasters(restored)) {
        auto const it = std::find_if(written.begin(), written.end(),
                                     [&](io::GrainState const& w) { return w.uid == g.uid; });
        ASSERT_NE(it, written.end());
        EXPECT_EQ(int{g.flags.bits()}, int{it->flags.bits()}) << "uid " << g.uid;
    }
}

TEST(Checkpoint, DatasetsCarryUnitsAndDescription) {
    using test::datasetText;
    core::Comm const world;
    std::string const path = fileName(world, "attributes");
    writeSample(world, path);
    world.barrier();
    EXPECT_EQ(datasetText(path, "position", "units"), "length");
    EXPECT_EQ(datasetText(path, "velocity", "units"), "length/time");
    EXPECT_EQ(datasetText(path, "force", "units"), "mass length/time^2");
    EXPECT_EQ(datasetText(path, "uid", "units"), "1");
    EXPECT_EQ(datasetText(path, "mass", "description"), "mass");
    // Every dataset has both (a file with grains and contact history: all columns written).
    for (char const* set :
         {"uid", "position", "velocity", "angular_velocity", "orientation", "force", "torque",
          "radius", "mass", "type", "flags", "gravity_reference", "gravity_field", "gravity_slope",
          "history_offset", "history_count", "history_partner", "history_spring",
          "history_stamp"}) {
        EXPECT_FALSE(datasetText(path, set, "units").empty()) << set;
        EXPECT_FALSE(datasetText(path, set, "description").empty()) << set;
    }
}

TEST(Checkpoint, SceneTextBeyond64KiBRoundTrips) {
    // A scene listing a few thousand grains: an HDF5 attribute in the object header stops at
    // 64 KiB, and the write failed (the run aborted at its first checkpoint).
    core::Comm const world;
    std::string const path = fileName(world, "large_scene");
    domain::BlockForest const forest(world, spec());
    auto const grains = io::collectMasters(fill(forest));
    io::CheckpointInfo written = info();
    for (int k = 0; written.scene.size() < 200'000; ++k)
        written.scene += fmt::format("  [{}.0, 1.5, 2.5],\n", k);
    io::writeCheckpoint(world, path, written, grains);
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    EXPECT_EQ(slice.info.scene, written.scene);
    EXPECT_EQ(slice.info.grainCount, 64U);
}

TEST(Checkpoint, FailedRenameLeavesNoTemporary) {
    // A directory where the checkpoint goes: the rename fails, every rank gets the error, and
    // the temporary is removed (it stayed behind, a full-size file per failed checkpoint).
    core::Comm const world;
    std::string const path = fileName(world, "blocked");
    if (world.rank() == 0) {
        fs::remove_all(path);
        fs::create_directories(path + "/x");
    }
    world.barrier();
    domain::BlockForest const forest(world, spec());
    io::CheckpointInfo written = info();
    try {
        io::writeCheckpoint(world, path, written, io::collectMasters(fill(forest)));
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find("renaming '" + path + ".tmp"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(hasTemporary(path));
    world.barrier();
    if (world.rank() == 0)
        fs::remove_all(path);
}

TEST(Checkpoint, LeftoverTemporaryLinkIsNotWrittenThrough) {
    // Links where a temporary would go (the name written before, and the one rank 0's process
    // takes first): their target keeps its content, and the checkpoint is a file of its own.
    core::Comm const world;
    std::string const path = fileName(world, "leftover");
    std::string const victim = fileName(world, "victim");
    long const pid = world.allReduce(world.rank() == 0 ? static_cast<long>(::getpid()) : 0L,
                                     core::ReduceOp::Sum);
    std::vector<std::string> const links{path + ".tmp", fmt::format("{}.tmp{}", path, pid)};
    if (world.rank() == 0) {
        fs::remove(path);
        std::ofstream(victim) << "keep";
        for (std::string const& link : links) {
            fs::remove(link);
            fs::create_symlink(victim, link);
        }
    }
    world.barrier();
    domain::BlockForest const forest(world, spec());
    io::CheckpointInfo written = info();
    io::writeCheckpoint(world, path, written, io::collectMasters(fill(forest)));
    world.barrier();
    std::ifstream in(victim);
    std::string content;
    std::getline(in, content);
    EXPECT_EQ(content, "keep");
    EXPECT_FALSE(fs::is_symlink(path));
    EXPECT_EQ(io::readCheckpoint(world, path).info.grainCount, 64U);
    for (std::string const& link : links)
        EXPECT_TRUE(fs::is_symlink(link)) << link; // not the writer's to remove
    world.barrier();
    if (world.rank() == 0) {
        for (std::string const& link : links)
            fs::remove(link);
        fs::remove(victim);
        fs::remove(path);
    }
}

TEST(Checkpoint, SelfGravityStateSurvivesBitForBit) {
    // The self-gravity state (format 2): per grain its reference position and cached field
    // (NaN rows for grains without one), and the run-wide update count and energy. Each rank
    // writes every P-th grain; the slices read back hash equal to what was written.
    core::Comm const world;
    std::string const path = fileName(world, "gravity");
    std::vector<io::GrainState> all = allGrains();
    for (std::size_t k = 0; k < all.size(); ++k)
        if (k % 4 != 3) {
            all[k].gravityReference = all[k].position + Vec3(1e-3, -0.0, 1.0 / 3.0);
            all[k].gravityField = Vec3(-1e-7 * static_cast<double>(k), 2.5e-300, -0.0);
        }
    std::vector<io::GrainState> mine;
    for (std::size_t k = static_cast<std::size_t>(world.rank()); k < all.size();
         k += static_cast<std::size_t>(world.size()))
        mine.push_back(all[k]);
    io::CheckpointInfo i = info();
    i.gravityUpdates = 17;
    i.gravityPotentialEnergy = -1.0 / 3.0;
    (void)io::writeCheckpoint(world, path, i, mine);
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    EXPECT_EQ(slice.info.gravityUpdates, 17);
    EXPECT_EQ(slice.info.gravityPotentialEnergy, -1.0 / 3.0);
    long long found = 0;
    for (io::GrainState const& g : slice.grains) {
        auto const it = std::find_if(all.begin(), all.end(),
                                     [&](io::GrainState const& a) { return a.uid == g.uid; });
        ASSERT_NE(it, all.end());
        EXPECT_EQ(io::grainHash(*it), io::grainHash(g)) << "uid " << g.uid;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(g.gravityField.z()),
                  std::bit_cast<std::uint64_t>(it->gravityField.z()));
        EXPECT_EQ(std::isnan(g.gravityReference.x()), std::isnan(it->gravityReference.x()));
        ++found;
    }
    EXPECT_EQ(world.allReduce(found, core::ReduceOp::Sum), 64);
}

TEST(Checkpoint, OtherRankCountReadsTheSameGrains) {
    // What all ranks wrote, read back by ranks 0 and 1 only (or rank 0 alone on one rank).
    core::Comm const world;
    std::string const path = fileName(world, "subset");
    writeSample(world, path);
    MPI_Comm half = MPI_COMM_NULL;
    MPI_Comm_split(world.raw(), world.rank() < 2 ? 0 : 1, world.rank(), &half);
    {
        core::Comm const sub(half);
        domain::BlockForest const forest(sub, spec());
        io::CheckpointSlice const slice = io::readCheckpoint(sub, path);
        particles::LocalParticles restored(forest);
        io::restoreGrains(sub, restored, slice.grains, "test");
        auto const count =
            sub.allReduce(static_cast<long long>(restored.countMasters()), core::ReduceOp::Sum);
        EXPECT_EQ(count, 64);
        expectSame(sortedMasters(fill(forest)), sortedMasters(restored));
    }
    MPI_Comm_free(&half);
}

TEST(Checkpoint, IdleRanksWriteAndReadNothing) {
    // Two blocks: on 4 ranks two ranks own no block and no grain, yet join every collective.
    core::Comm const world;
    domain::ForestSpec s = spec();
    s.rootBlocks = {2, 1, 1};
    domain::BlockForest const forest(world, s);
    particles::LocalParticles local(forest);
    for (io::GrainState const& g : allGrains())
        (void)local.addMaster(io::toParticleInit(g));
    std::string const path = fileName(world, "idle");
    io::CheckpointInfo i = info();
    io::writeCheckpoint(world, path, i, io::collectMasters(local));
    EXPECT_EQ(i.grainCount, 64U);
    io::CheckpointSlice const slice = io::readCheckpoint(world, path);
    particles::LocalParticles restored(forest);
    io::restoreGrains(world, restored, slice.grains, "test");
    EXPECT_EQ(restored.countMasters(), local.countMasters());
    EXPECT_EQ(world.allReduce(static_cast<long long>(restored.countMasters()), core::ReduceOp::Sum),
              64);
}

TEST(Checkpoint, TruncatedFileIsRefused) {
    core::Comm const world;
    std::string const path = fileName(world, "truncated");
    writeSample(world, path);
    if (world.rank() == 0)
        fs::resize_file(path, fs::file_size(path) / 2);
    world.barrier();
    std::string const before = fileBytes(path);
    std::string const message = readError(world, path);
    EXPECT_NE(message.find("checkpoint '" + path + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("truncated or damaged"), std::string::npos) << message;
    EXPECT_EQ(fileBytes(path), before);
}

TEST(Checkpoint, FlippedDataByteIsRefused) {
    core::Comm const world;
    std::string const path = fileName(world, "flipped");
    writeSample(world, path);
    if (world.rank() == 0) {
        // One bit of the middle of the velocity dataset: HDF5 itself cannot notice it.
        hid_t const file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
        hid_t const set = H5Dopen2(file, "velocity", H5P_DEFAULT);
        auto const offset = static_cast<std::streamoff>(H5Dget_offset(set) + 64 * 3 * 8 / 2);
        H5Dclose(set);
        H5Fclose(file);
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(offset);
        char c = 0;
        f.get(c);
        f.seekp(offset);
        f.put(static_cast<char>(c ^ 0x10));
    }
    world.barrier();
    std::string const message = readError(world, path);
    EXPECT_NE(message.find("checkpoint '" + path + "': checksum mismatch"), std::string::npos)
        << message;
}

TEST(Checkpoint, ImpossibleGrainCountIsRefusedBeforeAllocating) {
    // A damaged grain_count sized the read buffers before the checksum was checked: 2^62 ended
    // in std::bad_alloc (an internal error and MPI_Abort) instead of an input error.
    core::Comm const world;
    std::string const path = fileName(world, "grain_count");
    writeSample(world, path);
    if (world.rank() == 0)
        overwriteAttribute(path, "grain_count", H5T_NATIVE_UINT64, std::uint64_t{1} << 62);
    world.barrier();
    std::string const message = readError(world, path);
    EXPECT_NE(message.find("checkpoint '" + path + "': 4611686018427387904 grains"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("cannot fit in its"), std::string::npos) << message;
}

TEST(Checkpoint, OtherFormatVersionOrNoneIsRefused) {
    core::Comm const world;
    std::string const path = fileName(world, "version");
    writeSample(world, path);
    if (world.rank() == 0)
        overwriteAttribute(path, "format_version", H5T_NATIVE_INT64, std::int64_t{99});
    world.barrier();
    std::string const message = readError(world, path);
    EXPECT_NE(message.find(fmt::format("format version 99, this build reads version {}",
                                       io::kCheckpointFormatVersion)),
              std::string::npos)
        << message;
    // Without the attribute: another program's HDF5 file, or damaged metadata.
    if (world.rank() == 0) {
        hid_t const file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
        H5Adelete(file, "format_version");
        H5Fclose(file);
    }
    world.barrier();
    EXPECT_NE(readError(world, path)
                  .find("'format_version' is missing (not a Regolith "
                        "checkpoint, or a damaged one)"),
              std::string::npos);
}

TEST(Checkpoint, MissingFileIsRefused) {
    core::Comm const world;
    EXPECT_EQ(readError(world, "no_such_checkpoint.h5"),
              "checkpoint 'no_such_checkpoint.h5': no such file");
    EXPECT_EQ(readError(world, "."), "checkpoint '.': is a directory, not a checkpoint file");
}

TEST(Checkpoint, GrainOutsideTheDomainIsRefused) {
    core::Comm const world;
    domain::BlockForest const forest(world, spec());
    particles::LocalParticles local(forest);
    std::vector<io::GrainState> grains;
    if (world.rank() == world.size() - 1) {
        grains = allGrains();
        grains[5].position.z() = 9.0; // beyond the non-periodic z face
    }
    try {
        io::restoreGrains(world, local, grains, "ctx");
        ADD_FAILURE() << "no error";
    } catch (core::InputError const& e) {
        EXPECT_NE(std::string(e.what()).find("ctx: grain uid 1035 at [2.5, 2.5, 9] lies outside"),
                  std::string::npos)
            << e.what();
    }
}
