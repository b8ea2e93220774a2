#pragma once
/// The result of TimerTree::reduce: per phase, the time spent on each rank reduced to
/// minimum / average / maximum over ranks, and a formatted table of it.
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace regolith::core {

/// One phase (node of the timer tree) reduced over ranks. A rank that never entered the phase
/// counts as 0 s and 0 calls, so `min` is 0 when some rank lacks it.
struct TimerStats {
    std::string path;           ///< "step/sync/exchange"
    std::string name;           ///< last component: "exchange"
    int depth = 0;              ///< 0 for a top-level phase
    double min = 0.0;           ///< seconds, minimum over ranks
    double avg = 0.0;           ///< seconds, sum over ranks / number of ranks
    double max = 0.0;           ///< seconds, maximum over ranks
    std::uint64_t callsMin = 0; ///< calls, minimum over ranks
    std::uint64_t callsMax = 0; ///< calls, maximum over ranks
    std::uint64_t callsSum = 0; ///< calls, sum over ranks
};

/// Reduced timers of all ranks, in tree order (pre-order: a phase precedes its sub-phases,
/// siblings in order of first appearance, rank 0's first). Identical on every rank.
class TimerReport {
public:
    TimerReport() = default;
    TimerReport(int ranks, std::vector<TimerStats> rows)
        : m_ranks(ranks)
        , m_rows(std::move(rows)) {}

    /// Number of ranks reduced over.
    [[nodiscard]] int ranks() const { return m_ranks; }
    [[nodiscard]] std::vector<TimerStats> const& rows() const { return m_rows; }
    /// The row of `path`, or nullptr if no rank timed it.
    [[nodiscard]] TimerStats const* find(std::string_view path) const;

    /// A fixed-width table, one line per phase, sub-phases indented by two spaces:
    /// phase, calls (max over ranks), min/avg/max seconds and the imbalance max/avg.
    [[nodiscard]] std::string format() const;

private:
    int m_ranks = 0;
    std::vector<TimerStats> m_rows;
};

} // namespace regolith::core
