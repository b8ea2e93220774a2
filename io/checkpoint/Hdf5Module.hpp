#pragma once
/// Every HDF5 call of the checkpoints sits behind this interface, implemented by a shared
/// module (libregolith_hdf5.so: Hdf5Module.cpp with Hdf5Handle and Hdf5Attributes) that is
/// loaded with dlopen the first time a run writes or reads a checkpoint
/// (core/module/SharedModule.hpp). A run without checkpoints then maps none of HDF5's
/// libraries (with the TLS, Kerberos and LDAP libraries that Debian's HDF5 brings: 5.9 MB of
/// resident pages in every process; docs/notes/memory.md). No HDF5 header here. Errors
/// are core::InputError / core::Error (header-only) with the messages of the file layout's
/// checks.
#include "io/checkpoint/CheckpointInfo.hpp"

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace regolith::io::detail {

/// The element type of a column, mapped to an HDF5 type by the module.
enum class ColumnType { U64, U32, U8, F64 };

/// One column seen untyped: dataset name, element type, values per row, data, whether it is
/// a history column (H rows) or a grain column (N rows), and the dataset's `units` (in the
/// scene's unit system: "length", "mass length/time^2", "1" for pure numbers) and
/// `description` attributes.
struct ColumnView {
    char const* name;
    ColumnType type;
    std::size_t width;
    void* data;
    bool history;
    char const* units;
    char const* description;
};

/// Rows of this rank and where they start in the file.
struct Slab {
    std::uint64_t global = 0;
    std::uint64_t offset = 0;
    std::uint64_t local = 0;
};

/// What a checkpoint holds, written in one go.
struct CheckpointContent {
    CheckpointInfo const* info;
    std::uint64_t checksum;
    std::vector<ColumnView> const* columns; ///< every dataset, in the file's order
    Slab grains;                            ///< rows of the grain columns
    Slab entries;                           ///< rows of the history columns
};

/// An open checkpoint, read by this rank alone.
class CheckpointFile {
public:
    virtual ~CheckpointFile() = default;
    /// The format version alone (read first, so that a file of another version is named as
    /// such rather than as damaged). Throws core::InputError if it is missing.
    [[nodiscard]] virtual std::int64_t formatVersion() = 0;
    /// Every attribute; the stored checksum in `checksum`. Throws core::InputError for a
    /// missing or malformed attribute.
    [[nodiscard]] virtual CheckpointInfo info(std::uint64_t& checksum) = 0;
    /// Rows [first, first + rows) of `col` into col.data, after checking that the dataset
    /// exists and has `globalRows` rows of col.width. Throws core::InputError.
    virtual void readColumn(ColumnView const& col, std::uint64_t globalRows, std::uint64_t first,
                            std::uint64_t rows) = 0;
};

/// Failures the checkpoint tests provoke (REGOLITH_TEST_* variables, CheckpointWriter.cpp).
struct CheckpointFaults {
    /// Exit with code 86 after half the datasets (a crash mid-write).
    bool abortMidway = false;
    /// This rank reports its part of the dataset after half of them as failed (-1: none),
    /// after the collective write returned on every rank, as a full disk does on one rank.
    int failingRank = -1;
};

class Hdf5Module {
public:
    virtual ~Hdf5Module() = default;
    /// Creates `path` with the MPI-IO driver and writes `content` collectively: every rank its
    /// rows. An I/O failure (disk full, a quota) may hit one rank's part only: the ranks agree
    /// after every dataset, so that all stop together, close the file and throw
    /// core::InputError with the first failing rank's message (HDF5's innermost reason
    /// included) on every rank, rather than some waiting in the next collective write. The
    /// same if some rank cannot create the file. Messages start with `context`. COLLECTIVE
    /// over `comm`.
    virtual void write(MPI_Comm comm, std::string const& path, CheckpointContent const& content,
                       std::string const& context, CheckpointFaults faults) = 0;
    /// Opens `path` read-only. Throws core::InputError (prefixed with `context`) if it is not
    /// an HDF5 file or cannot be opened. Not collective.
    [[nodiscard]] virtual std::unique_ptr<CheckpointFile> open(std::string const& path,
                                                               std::string const& context) = 0;
};

/// The module, loaded on the first call (REGOLITH_HDF5_MODULE, else the build's copy, else
/// ../lib/ beside the executable), with HDF5's own error printing off: Regolith reports
/// failures itself, once. Throws core::Error naming the paths tried.
Hdf5Module& hdf5();

} // namespace regolith::io::detail

/// The module's one exported symbol.
extern "C" regolith::io::detail::Hdf5Module* regolith_hdf5_module();
