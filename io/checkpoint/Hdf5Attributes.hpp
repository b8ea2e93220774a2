#pragma once
/// Internal to the HDF5 module (Hdf5Module.hpp): the checkpoint's attributes (CheckpointInfo and
/// the checksum) and the HDF5 types of its columns.
#include "io/checkpoint/CheckpointInfo.hpp"
#include "io/checkpoint/Hdf5Module.hpp"

#include <hdf5.h>

#include <cstdint>
#include <string>

namespace regolith::io::detail {

/// The type a column has in the file (little endian, fixed size) and in memory (native).
[[nodiscard]] hid_t fileType(ColumnType t);
[[nodiscard]] hid_t memoryType(ColumnType t);

/// Writes every field of `info` and `checksum` as attributes of the root group. With the
/// MPI-IO driver every rank calls it with the same values (HDF5 metadata is collective).
/// Throws core::InputError prefixed with `context` on an HDF5 failure.
void writeInfoAttributes(hid_t file, CheckpointInfo const& info, std::uint64_t checksum,
                         std::string const& context);

/// Writes the string attribute `name` = `text` on the object `object` (a dataset, a group).
/// Throws core::InputError prefixed with `context` on an HDF5 failure.
void writeTextAttribute(hid_t object, char const* name, std::string const& text,
                        std::string const& context);

/// Reads the format version alone (first, so that a file of another version is named as such
/// rather than as damaged). Throws core::InputError prefixed with `context` if it is missing.
[[nodiscard]] std::int64_t readFormatVersion(hid_t file, std::string const& context);

/// Reads every field of CheckpointInfo; returns the stored checksum in `checksum`. Throws
/// core::InputError prefixed with `context` for a missing or malformed attribute.
[[nodiscard]] CheckpointInfo readInfoAttributes(hid_t file, std::uint64_t& checksum,
                                                std::string const& context);

} // namespace regolith::io::detail
