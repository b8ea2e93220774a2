#pragma once
/// The `--dump` file (docs/design.md, "Dump"): the masters of all ranks sorted by uid as
/// CSV, written by rank 0. Readable back as a `kind = "file"` particle source.
#include "apps/common/MasterRecord.hpp"
#include "core/mpi/Comm.hpp"

#include <span>
#include <string>

namespace regolith::apps {

/// The header line of the dump (with its newline): the dump columns of the table's entries
/// marked kDump (particles/storage/GrainQuantities.hpp: uid,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass),
/// then a column per declared grain-field component (`name`, or `name_x,name_y,name_z`).
[[nodiscard]] std::string dumpHeader();

/// The dump text of `masters` (one rank's or all): dumpHeader(), then one line per master in
/// increasing uid, every floating-point number with "{:.17g}" (17 significant digits: reads
/// back to the same double) and integers (the uid) as integers. Not collective.
[[nodiscard]] std::string dumpCsv(std::span<MasterRecord const> masters);

/// Gathers the masters of every rank on rank 0 and returns dumpCsv of all of them there ("" on
/// the other ranks): the same bytes for any number of ranks and any distribution. Throws
/// core::InputError on every rank if rank 0 would receive 2^31 bytes or more (the limit of
/// one MPI_Gatherv); memory on rank 0 is O(global masters). COLLECTIVE over `comm`.
[[nodiscard]] std::string gatherDumpCsv(core::Comm const& comm,
                                        std::span<MasterRecord const> local);

} // namespace regolith::apps
