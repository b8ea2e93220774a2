#include "coupling/gravity/ForceErrorMonitor.hpp"

namespace regolith::coupling {

void ForceErrorMonitor::afterStep(bool updated, long long updates, long long steps) {
    if (!updated || m_armed)
        return;
    if (m_schedule.everyUpdates > 0) {
        m_armed = updates % m_schedule.everyUpdates == 0;
    } else if (m_schedule.spacingSteps > 0 && steps > m_nextArmStep) {
        m_armed = true;
        while (m_nextArmStep < steps)
            m_nextArmStep += m_schedule.spacingSteps;
    }
}

void ForceErrorMonitor::record(std::vector<double> const& errors) {
    m_armed = false;
    ++m_checks;
    m_errors.insert(m_errors.end(), errors.begin(), errors.end());
    m_stats = gravity::summarizeErrors(m_errors);
}

} // namespace regolith::coupling
