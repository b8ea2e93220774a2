#pragma once
/// The .pvd time series VtkOutput writes, read back (to continue a series after a restart,
/// and for regolith-render).
#include <string>
#include <vector>

namespace regolith::io {

/// One entry of a .pvd time series.
struct SeriesEntry {
    double time = 0.0;
    std::string file; ///< as written in the .pvd (relative to its directory)
};

/// The data sets of the .pvd at `path`, in file order. Throws core::InputError naming the
/// file if it cannot be read or is not a VTK collection. Not collective.
[[nodiscard]] std::vector<SeriesEntry> readSeries(std::string const& path);

} // namespace regolith::io
