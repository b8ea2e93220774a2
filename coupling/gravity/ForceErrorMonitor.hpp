#pragma once
/// The force error a run's grains actually feel, measured during the run (`gravity.check_every`):
/// after every n-th field update (or, "auto", after the first update of each eighth of the run)
/// a check is armed; it is taken at the next update, on the field the integrator applied in
/// the step before it — the stalest of that interval, extrapolation included — against the
/// direct sum at that step's positions, on a sample of grains chosen by uid (the same grains on
/// any layout, SampledForceError.hpp). The errors of all checks are pooled; their median and
/// 99th percentile are the run's measured accuracy.
#include "gravity/common/ForceError.hpp"

#include <cstddef>
#include <vector>

namespace regolith::coupling {

/// When checks are armed. Both 0: never.
struct ForceCheckSchedule {
    long long everyUpdates = 0; ///< after every n-th update (gravity.check_every = n)
    long long spacingSteps = 0; ///< "auto": after the first update at or past every multiple
    std::size_t sample = 300;   ///< grains per check, over all ranks
};

class ForceErrorMonitor {
public:
    explicit ForceErrorMonitor(ForceCheckSchedule schedule)
        : m_schedule(schedule) {}

    /// After the forces of a step were applied: `updated` whether this step computed a new
    /// field, `updates` the updates so far, `steps` the steps so far (this one included). Arms
    /// a check as scheduled. The same on every rank (its arguments are). Not collective.
    void afterStep(bool updated, long long updates, long long steps);
    /// Whether a check waits for the next update (keep each step's positions and applied field
    /// until then).
    [[nodiscard]] bool armed() const { return m_armed; }
    /// Adds one check's sampled errors (the same on every rank) and disarms. Not collective.
    void record(std::vector<double> const& errors);

    [[nodiscard]] long long checks() const { return m_checks; }
    /// Median, p99 and maximum over all checks' samples (count: the samples).
    [[nodiscard]] gravity::ErrorStats const& stats() const { return m_stats; }
    [[nodiscard]] std::size_t sample() const { return m_schedule.sample; }

private:
    ForceCheckSchedule m_schedule;
    bool m_armed = false;
    long long m_nextArmStep = 0; ///< "auto": the next multiple of spacingSteps
    long long m_checks = 0;
    std::vector<double> m_errors; ///< every check's samples
    gravity::ErrorStats m_stats;
};

} // namespace regolith::coupling
