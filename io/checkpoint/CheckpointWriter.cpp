#include "io/checkpoint/CheckpointWriter.hpp"

#include "core/Error.hpp"
#include "core/file/Files.hpp"
#include "io/checkpoint/GrainColumns.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <system_error>
#include <unistd.h>

namespace regolith::io {

namespace {

using detail::Slab;

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

/// The failures the checkpoint tests ask for at `step`: REGOLITH_TEST_ABORT_IN_CHECKPOINT=<step>
/// (a crash mid-write), REGOLITH_TEST_FAIL_IN_CHECKPOINT=<step>:<rank> (that rank's write
/// fails, as on a full disk).
detail::CheckpointFaults faultsRequestedAt(std::int64_t step) {
    detail::CheckpointFaults faults;
    char const* abort = std::getenv("REGOLITH_TEST_ABORT_IN_CHECKPOINT");
    faults.abortMidway = abort != nullptr && std::string(abort) == std::to_string(step);
    char const* fail = std::getenv("REGOLITH_TEST_FAIL_IN_CHECKPOINT");
    std::string const prefix = std::to_string(step) + ":";
    if (fail != nullptr && std::string(fail).starts_with(prefix))
        faults.failingRank = std::atoi(fail + prefix.size());
    return faults;
}

/// Makes the closed temporary file durable before it replaces the old one.
void syncToDisk(std::string const& file) {
    int const fd = ::open(file.c_str(), O_RDONLY);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
}

} // namespace

std::uint64_t writeCheckpoint(core::Comm const& comm, std::string const& path, CheckpointInfo& info,
                              std::span<GrainState const> grains) {
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

    // A fresh temporary beside the checkpoint, made by rank 0 and written by all: a leftover
    // one (a link, say) is never written through.
    std::string tmp;
    std::string why;
    if (comm.rank() == 0) {
        tmp = core::createTemporaryBeside(path, why);
        if (tmp.empty())
            why = fmt::format("{}: {}", context, why);
    }
    comm.broadcast(why, 0);
    if (!why.empty())
        throw core::InputError(why);
    comm.broadcast(tmp, 0);
    std::vector<detail::ColumnView> const views = detail::columnViews(columns);
    try {
        detail::hdf5().write(comm.raw(), tmp, {&info, checksum, &views, grainSlab, entrySlab},
                             context, faultsRequestedAt(info.step));
    } catch (core::InputError const& e) { // on every rank: no stale temporary left behind
        // HDF5 does not pass the operating system's reason on: name the space left, the
        // usual cause.
        std::string space;
        if (comm.rank() == 0) {
            std::error_code ec;
            auto const dir = std::filesystem::absolute(path, ec).parent_path();
            auto const free = std::filesystem::space(dir, ec);
            if (!ec)
                space = fmt::format("; {} bytes were free on the file system of '{}'",
                                    free.available, dir.string());
            std::filesystem::remove(tmp, ec);
        }
        comm.broadcast(space, 0);
        throw core::InputError(e.what() + space);
    }
    comm.barrier(); // every rank's data is in the closed file
    std::string failure;
    std::uint64_t bytes = 0;
    if (comm.rank() == 0) {
        syncToDisk(tmp);
        std::error_code ec;
        bytes = std::filesystem::file_size(tmp, ec);
        std::filesystem::rename(tmp, path, ec);
        if (ec) {
            failure = fmt::format("{}: renaming '{}' failed: {}", context, tmp, ec.message());
            std::filesystem::remove(tmp, ec); // no stale temporary beside the checkpoints
        }
    }
    comm.broadcast(failure, 0);
    if (!failure.empty())
        throw core::InputError(failure);
    unsigned long long b = bytes;
    core::Comm::check(MPI_Bcast(&b, 1, MPI_UNSIGNED_LONG_LONG, 0, comm.raw()), "MPI_Bcast");
    return b;
}

} // namespace regolith::io
