#pragma once
/// Relative force error of an approximate method against a reference (the direct sum):
/// |a - a_ref| / |a_ref| per grain, summarised by median, 99th percentile and maximum.
#include "core/mpi/Comm.hpp"

#include <span>
#include <vector>

namespace regolith::gravity {

struct ErrorStats {
    double median = 0.0;
    double p99 = 0.0; ///< 99th percentile (nearest rank)
    double max = 0.0;
    long long count = 0; ///< grains over all ranks
};

/// Accelerations of n grains in SoA.
struct AccelView {
    std::span<double const> ax, ay, az;
};

/// Per-grain relative errors of `approx` against `reference` (same grains, same order).
/// A grain with zero reference acceleration has error |a| (absolute). Not collective.
[[nodiscard]] std::vector<double> relativeErrors(AccelView approx, AccelView reference);

/// Statistics of `errors` as they are (one rank's, or errors every rank holds alike). Not
/// collective.
[[nodiscard]] ErrorStats summarizeErrors(std::vector<double> errors);

/// Statistics of the errors of all grains on all ranks (gathers the errors). COLLECTIVE over
/// `comm`.
[[nodiscard]] ErrorStats errorStats(core::Comm const& comm, std::span<double const> errors);

} // namespace regolith::gravity
