#include "io/checkpoint/CheckpointReader.hpp"

#include "core/Error.hpp"
#include "io/checkpoint/GrainColumns.hpp"
#include "io/checkpoint/Hdf5Attributes.hpp"
#include "io/checkpoint/Hdf5Handle.hpp"
#include "io/detail/AgreeOnError.hpp"

#include <fmt/format.h>

#include <array>
#include <filesystem>

namespace regolith::io {

namespace {

using detail::h5check;
using detail::H5Handle;
using detail::h5own;

/// Reads rows [first, first + rows) of one column after checking the dataset's shape.
void readColumn(hid_t file, detail::ColumnView const& col, std::uint64_t globalRows,
                std::uint64_t first, std::uint64_t rows, std::string const& context) {
    std::string const what = std::string("dataset '") + col.name + "'";
    if (H5Lexists(file, col.name, H5P_DEFAULT) <= 0)
        throw core::InputError(context + ": " + what + " is missing");
    H5Handle const set =
        h5own(H5Dopen2(file, col.name, H5P_DEFAULT), H5Dclose, context, what.c_str());
    H5Handle const fileSpace = h5own(H5Dget_space(set.get()), H5Sclose, context, what.c_str());
    int const rank = col.width > 1 ? 2 : 1;
    std::array<hsize_t, 2> dims{0, 0};
    if (H5Sget_simple_extent_ndims(fileSpace.get()) != rank ||
        H5Sget_simple_extent_dims(fileSpace.get(), dims.data(), nullptr) != rank ||
        dims[0] != globalRows || (rank == 2 && dims[1] != col.width))
        throw core::InputError(fmt::format("{}: {} has the wrong shape (expected {} x {})", context,
                                           what, globalRows, col.width));
    if (rows == 0)
        return;
    std::array<hsize_t, 2> const start{first, 0};
    std::array<hsize_t, 2> const count{rows, col.width};
    h5check(H5Sselect_hyperslab(fileSpace.get(), H5S_SELECT_SET, start.data(), nullptr,
                                count.data(), nullptr),
            context, "H5Sselect_hyperslab");
    H5Handle const memSpace =
        h5own(H5Screate_simple(rank, count.data(), nullptr), H5Sclose, context, "H5Screate");
    h5check(H5Dread(set.get(), detail::memoryType(col.type), memSpace.get(), fileSpace.get(),
                    H5P_DEFAULT, col.data),
            context, what.c_str());
}

/// This rank's part of the file, and the sum of its grain hashes.
CheckpointSlice readLocal(core::Comm const& comm, std::string const& path,
                          std::string const& context, std::uint64_t& storedChecksum,
                          std::uint64_t& hashSum) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw core::InputError(context + ": no such file");
    if (H5Fis_hdf5(path.c_str()) <= 0)
        throw core::InputError(context + ": not an HDF5 file (truncated or damaged?)");
    hid_t const opened = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (opened < 0)
        throw core::InputError(context + ": HDF5 cannot open it (truncated or damaged file)");
    H5Handle const file(opened, H5Fclose);
    std::int64_t const version = detail::readFormatVersion(file.get(), context);
    if (version != kCheckpointFormatVersion)
        throw core::InputError(fmt::format("{}: format version {}, this build reads version {}",
                                           context, version, kCheckpointFormatVersion));
    CheckpointSlice out;
    out.info = detail::readInfoAttributes(file.get(), storedChecksum, context);

    auto const n = out.info.grainCount;
    auto const p = static_cast<std::uint64_t>(comm.size());
    auto const r = static_cast<std::uint64_t>(comm.rank());
    std::uint64_t const first = n / p * r + std::min(r, n % p);
    std::uint64_t const rows = n / p + (r < n % p ? 1 : 0);
    // Grain columns first: the history offsets say which entries this slice needs.
    detail::GrainColumns columns;
    columns.resize(rows, 0);
    for (auto const& col : detail::columnViews(columns))
        if (!col.history)
            readColumn(file.get(), col, n, first, rows, context);
    std::uint64_t entryFirst = 0;
    std::uint64_t entryEnd = 0;
    if (rows > 0) {
        entryFirst = columns.historyOffset.front();
        entryEnd = columns.historyOffset.back() + columns.historyCount.back();
    }
    if (entryFirst > entryEnd || entryEnd > out.info.historyCount)
        throw core::InputError(context + ": history offsets point outside the history datasets");
    columns.resize(rows, entryEnd - entryFirst);
    for (auto const& col : detail::columnViews(columns))
        if (col.history)
            readColumn(file.get(), col, out.info.historyCount, entryFirst, entryEnd - entryFirst,
                       context);
    out.grains = detail::fromColumns(columns, entryFirst, context);
    hashSum = 0;
    for (GrainState const& g : out.grains)
        hashSum += grainHash(g);
    return out;
}

} // namespace

CheckpointSlice readCheckpoint(core::Comm const& comm, std::string const& path) {
    detail::silenceHdf5Errors();
    std::string const context = "checkpoint '" + path + "'";
    std::uint64_t stored = 0;
    std::uint64_t hashSum = 0;
    CheckpointSlice out;
    detail::agreeOnError(comm, [&] { out = readLocal(comm, path, context, stored, hashSum); });
    unsigned long long const local = hashSum;
    std::uint64_t const computed = infoHash(out.info) + comm.allReduce(local, core::ReduceOp::Sum);
    if (computed != stored)
        throw core::InputError(fmt::format(
            "{}: checksum mismatch (stored {:016x}, computed {:016x}): the file is damaged",
            context, stored, computed));
    return out;
}

} // namespace regolith::io
