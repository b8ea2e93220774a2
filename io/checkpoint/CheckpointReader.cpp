#include "io/checkpoint/CheckpointReader.hpp"

#include "core/Error.hpp"
#include "core/mpi/AgreeOnInputError.hpp"
#include "io/checkpoint/GrainColumns.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <memory>

namespace regolith::io {

namespace {

/// This rank's part of the file, and the sum of its grain hashes.
CheckpointSlice readLocal(core::Comm const& comm, std::string const& path,
                          std::string const& context, std::uint64_t& storedChecksum,
                          std::uint64_t& hashSum) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw core::InputError(context + (std::filesystem::is_directory(path, ec)
                                              ? ": is a directory, not a checkpoint file"
                                          : std::filesystem::exists(path, ec)
                                              ? ": not a regular file"
                                              : ": no such file"));
    std::unique_ptr<detail::CheckpointFile> const file = detail::hdf5().open(path, context);
    std::int64_t const version = file->formatVersion();
    if (version != kCheckpointFormatVersion)
        throw core::InputError(fmt::format("{}: format version {}, this build reads version {}",
                                           context, version, kCheckpointFormatVersion));
    CheckpointSlice out;
    out.info = file->info(storedChecksum);

    // The counts size this rank's buffers: bound them by what the file can hold (at least a
    // byte per value) before allocating, so that a damaged count is an input error, not an
    // allocation of exabytes (the checksum is verified only after the reads).
    std::size_t grainValues = 0, entryValues = 0;
    detail::GrainColumns none;
    for (auto const& col : detail::columnViews(none))
        (col.history ? entryValues : grainValues) += col.width;
    std::uintmax_t const bytes = std::filesystem::file_size(path, ec);
    if (ec || out.info.grainCount > bytes / grainValues ||
        out.info.historyCount > bytes / entryValues)
        throw core::InputError(fmt::format(
            "{}: {} grains and {} history entries cannot fit in its {} bytes: the file is "
            "damaged",
            context, out.info.grainCount, out.info.historyCount, bytes));
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
            file->readColumn(col, n, first, rows);
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
            file->readColumn(col, out.info.historyCount, entryFirst, entryEnd - entryFirst);
    out.grains = detail::fromColumns(columns, entryFirst, context);
    hashSum = 0;
    for (GrainState const& g : out.grains)
        hashSum += grainHash(g);
    return out;
}

} // namespace

CheckpointSlice readCheckpoint(core::Comm const& comm, std::string const& path) {
    std::string const context = "checkpoint '" + path + "'";
    std::uint64_t stored = 0;
    std::uint64_t hashSum = 0;
    CheckpointSlice out;
    core::agreeOnInputError(comm, [&] { out = readLocal(comm, path, context, stored, hashSum); });
    unsigned long long const local = hashSum;
    std::uint64_t const computed = infoHash(out.info) + comm.allReduce(local, core::ReduceOp::Sum);
    if (computed != stored)
        throw core::InputError(fmt::format(
            "{}: checksum mismatch (stored {:016x}, computed {:016x}): the file is damaged",
            context, stored, computed));
    return out;
}

} // namespace regolith::io
