#pragma once
/// The rubble-pile record (pile.file) read back for a restart. Its first line holds the pile's
/// scales at the end of the settling, `# mass=… bulk_radius=… omega_c=… spin=… centre_x=…
/// centre_y=… centre_z=… mean_grain_radius=…` (17 digits: a restart continues with the same
/// bits), the second the column names, then one row per record, the pile's centre
/// (centre_x, centre_y, centre_z) among the columns.
#include "core/math/Vec3.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace regolith::apps {

/// The pile's scales at the end of the settling.
struct PileReference {
    double mass = 0.0;
    core::Vec3 centre = core::Vec3::Zero();
    double bulkRadius = 0.0;
    double omegaC = 0.0; ///< sqrt(4 pi G rho_bulk / 3)
    double spin = 0.0;   ///< about the axis [rad/time]
    double meanGrainRadius = 0.0;
};

/// What a restart takes from the record.
struct ResumedRecord {
    PileReference reference;
    core::Vec3 centre = core::Vec3::Zero(); ///< the pile's, at the last row kept
    std::vector<double> spins;              ///< spin / omega_c of the rows kept
    std::optional<double> onset;            ///< that of the first kept row with mass shed
    std::string kept;                       ///< the header lines and the rows kept
};

/// The text of the record at `path`, "" if it cannot be read. Not collective.
[[nodiscard]] std::string readPileRecord(std::string const& path);

/// The record `text` (of the file `path`, for messages) up to the rows at times <= `until`.
/// Throws core::InputError naming pile.file if `text` is empty or not such a record. Not
/// collective.
[[nodiscard]] ResumedRecord resumeRecord(std::string_view text, double until,
                                         std::string const& path);

} // namespace regolith::apps
