// HDF5 checkpoints refused (io/checkpoint): a truncated file, a flipped data byte, an
// impossible grain count, another format version or none, a missing file and a grain outside
// the domain are refused with one message on every rank, and the file is left as it was.
#include "core/Error.hpp"
#include "domain/BlockForest.hpp"
#include "io/checkpoint/CheckpointReader.hpp"
#include "io/checkpoint/RestoreGrains.hpp"
#include "tests/io/CheckpointSample.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace regolith;
using namespace regolith::checkpointtest;
namespace fs = std::filesystem;

namespace {

/// Overwrites the root attribute `name` of the file at `path` (rank 0 only).
template <class T>
void overwriteAttribute(std::string const& path, char const* name, hid_t type, T value) {
    hid_t const file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t const attr = H5Aopen(file, name, H5P_DEFAULT);
    H5Awrite(attr, type, &value);
    H5Aclose(attr);
    H5Fclose(file);
}

/// The message readCheckpoint throws on every rank (or "" if it does not throw).
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
