#include "io/checkpoint/CheckpointWriter.hpp"

#include "core/Error.hpp"
#include "io/checkpoint/GrainColumns.hpp"
#include "io/checkpoint/Hdf5Attributes.hpp"
#include "io/checkpoint/Hdf5Handle.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <array>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <system_error>
#include <unistd.h>

namespace regolith::io {

namespace {

using detail::h5check;
using detail::H5Handle;
using detail::h5own;

/// Rows of this rank and where they start in the file.
struct Slab {
    std::uint64_t global = 0;
    std::uint64_t offset = 0;
    std::uint64_t local = 0;
};

Slab slabOf(core::Comm const& comm, std::uint64_t local) {
    Slab s;
    s.local = local;
    unsigned long long const mine = local;
    unsigned long long before = 0;
    core::Comm::check(MPI_Exscan(&mine, &before, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm.raw()),
                      "MPI_Exscan");
    s.offset = comm.rank() == 0 ? 0 : before; // MPI leaves rank 0's result undefined
    s.global = comm.allReduce(mine, core::ReduceOp::Sum);
    return s;
}

/// One dataset, written collectively: every rank its rows (none is fine).
void writeColumn(hid_t file, hid_t dxpl, detail::ColumnView const& col, Slab const& slab,
                 std::string const& context) {
    int const rank = col.width > 1 ? 2 : 1;
    std::array<hsize_t, 2> const dims{slab.global, col.width};
    std::array<hsize_t, 2> const start{slab.offset, 0};
    std::array<hsize_t, 2> const count{slab.local, col.width};
    H5Handle const fileSpace =
        h5own(H5Screate_simple(rank, dims.data(), nullptr), H5Sclose, context, "H5Screate");
    H5Handle const set = h5own(H5Dcreate2(file, col.name, detail::fileType(col.type),
                                          fileSpace.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                               H5Dclose, context, col.name);
    if (slab.global == 0)
        return; // nothing to write anywhere: every rank skips alike
    H5Handle const memSpace =
        h5own(H5Screate_simple(rank, count.data(), nullptr), H5Sclose, context, "H5Screate");
    if (slab.local > 0) {
        h5check(H5Sselect_hyperslab(fileSpace.get(), H5S_SELECT_SET, start.data(), nullptr,
                                    count.data(), nullptr),
                context, "H5Sselect_hyperslab");
    } else {
        h5check(H5Sselect_none(fileSpace.get()), context, "H5Sselect_none");
        h5check(H5Sselect_none(memSpace.get()), context, "H5Sselect_none");
    }
    // A rank without rows still joins the collective write; HDF5 wants a buffer anyway.
    static double const kNothing = 0.0;
    void const* data = col.data != nullptr ? col.data : &kNothing;
    h5check(H5Dwrite(set.get(), detail::memoryType(col.type), memSpace.get(), fileSpace.get(), dxpl,
                     data),
            context, col.name);
}

bool abortRequestedAt(std::int64_t step) {
    char const* v = std::getenv("REGOLITH_TEST_ABORT_IN_CHECKPOINT");
    return v != nullptr && std::string(v) == std::to_string(step);
}

/// Makes the closed temporary file durable before it replaces the old one.
void syncToDisk(std::string const& file) {
    int const fd = ::open(file.c_str(), O_RDONLY);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
}

/// Creates the file and writes everything; returns with the file closed.
void writeFile(core::Comm const& comm, std::string const& tmp, CheckpointInfo const& info,
               detail::GrainColumns& columns, Slab const& grains, Slab const& entries,
               std::uint64_t checksum, std::string const& context) {
    H5Handle const fapl = h5own(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, context, "H5Pcreate");
    h5check(H5Pset_fapl_mpio(fapl.get(), comm.raw(), MPI_INFO_NULL), context, "H5Pset_fapl_mpio");
    hid_t const created = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
    if (!comm.allTrue(created >= 0)) {
        if (created >= 0)
            H5Fclose(created);
        throw core::InputError(fmt::format(
            "{}: cannot create '{}' (does the directory exist and is it writable?)", context, tmp));
    }
    H5Handle file(created, H5Fclose);
    // From here on a failure is unexpected (I/O error, disk full) and may hit one rank only:
    // core::Error aborts the job rather than leaving ranks in a collective.
    try {
        H5Handle const dxpl = h5own(H5Pcreate(H5P_DATASET_XFER), H5Pclose, context, "H5Pcreate");
        h5check(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE), context, "H5Pset_dxpl_mpio");
        auto const views = detail::columnViews(columns);
        for (std::size_t k = 0; k < views.size(); ++k) {
            writeColumn(file.get(), dxpl.get(), views[k], views[k].history ? entries : grains,
                        context);
            if (k == views.size() / 2 && abortRequestedAt(info.step)) {
                H5Fflush(file.get(), H5F_SCOPE_GLOBAL);
                std::_Exit(86);
            }
        }
        detail::writeInfoAttributes(file.get(), info, checksum, context);
        h5check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), context, "H5Fflush");
        if (!file.reset())
            throw core::InputError(context + ": closing '" + tmp + "' failed");
    } catch (core::InputError const& e) {
        throw core::Error(e.what());
    }
}

} // namespace

std::uint64_t writeCheckpoint(core::Comm const& comm, std::string const& path, CheckpointInfo& info,
                              std::span<GrainState const> grains) {
    detail::silenceHdf5Errors();
    std::string const context = "cannot write checkpoint '" + path + "'";
    std::uint64_t localEntries = 0;
    unsigned long long localHash = 0;
    for (GrainState const& g : grains) {
        localEntries += g.history.size();
        localHash += grainHash(g); // wraps modulo 2^64: an order-independent multiset hash
    }
    Slab const grainSlab = slabOf(comm, grains.size());
    Slab const entrySlab = slabOf(comm, localEntries);
    info.formatVersion = kCheckpointFormatVersion;
    info.grainCount = grainSlab.global;
    info.historyCount = entrySlab.global;
    std::uint64_t const checksum = infoHash(info) + comm.allReduce(localHash, core::ReduceOp::Sum);
    detail::GrainColumns columns = detail::toColumns(grains, entrySlab.offset);

    std::string const tmp = path + ".tmp";
    writeFile(comm, tmp, info, columns, grainSlab, entrySlab, checksum, context);
    comm.barrier(); // every rank's data is in the closed file
    std::string failure;
    std::uint64_t bytes = 0;
    if (comm.rank() == 0) {
        syncToDisk(tmp);
        std::error_code ec;
        bytes = std::filesystem::file_size(tmp, ec);
        std::filesystem::rename(tmp, path, ec);
        if (ec)
            failure = fmt::format("{}: renaming '{}' failed: {}", context, tmp, ec.message());
    }
    comm.broadcast(failure, 0);
    if (!failure.empty())
        throw core::InputError(failure);
    unsigned long long b = bytes;
    core::Comm::check(MPI_Bcast(&b, 1, MPI_UNSIGNED_LONG_LONG, 0, comm.raw()), "MPI_Bcast");
    return b;
}

} // namespace regolith::io
