#include "particles/detection/ReferenceDepths.hpp"

#include "particles/detection/PairOwnership.hpp"

#include <algorithm>
#include <limits>

namespace regolith::particles {

void ReferenceDepths::start(VerletList const& list, core::AABB const& region,
                            PeriodicFrame const& frame) {
    m_emits = emittingBox(region, frame);
    m_period = frame.period();
    m_shifted = 0.0;
    m_depth.assign(list.builtSize(), kUnmeasured);
}

void ReferenceDepths::clear() {
    m_shifted = 0.0;
    m_depth.clear();
}

double ReferenceDepths::measure(VerletList const& list, ParticleStorage const& ps,
                                VerletList::Id id) const {
    if (id >= m_depth.size())
        return 0.0; // an arrival
    double& depth = m_depth[id];
    std::uint32_t const k = list.indexOf(id);
    if (k == VerletList::kDead)
        return depth = 0.0;
    // Measured where the references stood at the rebuild (deeperThan counts the shifts).
    core::Vec3 const x = localPosition(list.unshiftedReference(id), ps.image(k), m_period);
    depth = std::numeric_limits<double>::infinity();
    for (int d = 0; d < 3 && depth > 0.0; ++d) {
        double const below = x[d] - m_emits.min[d], above = m_emits.max[d] - x[d];
        depth = below > 0.0 && above > 0.0 ? std::min({depth, below, above}) : 0.0;
    } // outside, or not finite: 0
    return depth;
}

} // namespace regolith::particles
