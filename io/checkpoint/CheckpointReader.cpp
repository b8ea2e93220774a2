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
        throw core::InputError(context + ": no such file");
    std::unique_ptr<detail::CheckpointFile> const file = detail::hdf5().open(path, context);
    std::int64_t const version = file->formatVersion();
    if (version != kCheckpointFormatVersion)
        throw core::InputError(fmt::format("{}: format version {}, this build reads version {}",
                                           context, version, kCheckpointFormatVersion));
    CheckpointSlice out;
    out.info = file->info(storedChecksum);

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
