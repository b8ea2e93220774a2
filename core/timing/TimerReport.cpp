#include "core/timing/TimerReport.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace regolith::core {

TimerStats const* TimerReport::find(std::string_view path) const {
    auto const it = std::find_if(m_rows.begin(), m_rows.end(),
                                 [path](TimerStats const& s) { return s.path == path; });
    return it == m_rows.end() ? nullptr : &*it;
}

std::string TimerReport::format() const {
    std::size_t width = 5; // "phase"
    for (auto const& r : m_rows)
        width = std::max(width, 2 * static_cast<std::size_t>(r.depth) + r.name.size());
    std::string out = fmt::format("{:<{}}  {:>10}  {:>12}  {:>12}  {:>12}  {:>8}\n", "phase", width,
                                  "calls", "min [s]", "avg [s]", "max [s]", "max/avg");
    for (auto const& r : m_rows) {
        std::string const label = std::string(2 * static_cast<std::size_t>(r.depth), ' ') + r.name;
        // An idle phase (avg 0) is perfectly balanced.
        double const imbalance = r.avg > 0.0 ? r.max / r.avg : 1.0;
        out += fmt::format("{:<{}}  {:>10}  {:>12.6f}  {:>12.6f}  {:>12.6f}  {:>8.3f}\n", label,
                           width, r.callsMax, r.min, r.avg, r.max, imbalance);
    }
    return out;
}

} // namespace regolith::core
