#pragma once
/// Reader of the grain CSV files of `kind = "file"` entries (format in FileSpec): a header
/// line naming the columns, then one grain per line. Every error is a core::InputError that
/// names the scene key, the file, the line and the column.
#include "core/math/Vec3.hpp"

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace regolith::particles {

/// One data line of a grain CSV file, as read (no range checks beyond "finite number").
struct CsvGrain {
    int line = 0; ///< 1-based line number in the file
    core::Vec3 position = core::Vec3::Zero();
    core::Vec3 velocity = core::Vec3::Zero();
    core::Vec3 angularVelocity = core::Vec3::Zero();
    double radius = 0.0;
    double density = 0.0;   ///< set iff the table has a density column
    double mass = 0.0;      ///< set iff the table has a mass column
    std::uint64_t uid = 0;  ///< set iff the table has a uid column
    std::uint32_t type = 0; ///< set iff the table has a type column
};

struct CsvGrainTable {
    std::vector<CsvGrain> grains; ///< in file order
    bool hasDensity = false;
    bool hasMass = false;
    bool hasUid = false;
    bool hasType = false;
    bool hasAngularVelocity = false; ///< a wx, wy or wz column
};

/// The column names a grain CSV may use.
[[nodiscard]] std::vector<std::string> const& grainCsvColumns();

/// Parses grain CSV text from `in`. `fileName` is used in messages, `key` is the scene key
/// the file came from (e.g. "particles[3].path"). Throws core::InputError for: an empty file
/// or header, an unknown, duplicate or missing required column, both density and mass, a
/// line with the wrong number of fields, a field that is not a finite number (uid and type:
/// a non-negative integer). Blank lines and lines whose first non-blank character is '#' are
/// skipped; fields may be padded with blanks; CRLF line ends are accepted.
[[nodiscard]] CsvGrainTable parseGrainCsv(std::istream& in, std::string const& fileName,
                                          std::string const& key);

/// Opens `path` and parses it (parseGrainCsv); throws core::InputError naming `key` and the
/// path if it is not a regular file (a FIFO would block, /dev/zero never end) or cannot be
/// opened, then naming `resolvedFrom` too if given (the folder a relative path was taken
/// from). Not collective: every rank may read the same file.
[[nodiscard]] CsvGrainTable readGrainCsv(std::string const& path, std::string const& key,
                                         std::string const& resolvedFrom = {});

} // namespace regolith::particles
