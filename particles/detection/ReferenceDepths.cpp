#include "particles/detection/ReferenceDepths.hpp"

#include "particles/detection/PairOwnership.hpp"

#include <algorithm>

namespace regolith::particles {

void ReferenceDepths::start(VerletList const& list, core::AABB const& region,
                            PeriodicFrame const& frame) {
    // From the domain's faces also where the cells wrap: a master that crosses one is a new
    // copy for the list, so its pairs must not keep their springs beside it.
    PeriodicFrame faces = frame;
    faces.wrapped = {false, false, false};
    m_emits = emittingBox(region, faces);
    m_period = frame.period();
    m_shifted = core::Vec3::Zero();
    m_depth.assign(list.builtSize(), Axes{kUnmeasured, kUnmeasured, kUnmeasured});
}

void ReferenceDepths::clear() {
    m_shifted = core::Vec3::Zero();
    m_depth.clear();
}

ReferenceDepths::Axes const& ReferenceDepths::measure(VerletList const& list,
                                                      ParticleStorage const& ps,
                                                      VerletList::Id id) const {
    static constexpr Axes kNone{0.0, 0.0, 0.0};
    if (id >= m_depth.size())
        return kNone; // an arrival
    Axes& depth = m_depth[id];
    std::uint32_t const k = list.indexOf(id);
    if (k == VerletList::kDead)
        return depth = kNone;
    // Measured where the references stood at the rebuild (deeperThan counts the shifts).
    core::Vec3 const x = localPosition(list.unshiftedReference(id), ps.image(k), m_period);
    for (int d = 0; d < 3; ++d) {
        double const below = x[d] - m_emits.min[d], above = m_emits.max[d] - x[d];
        if (!(below > 0.0 && above > 0.0))
            return depth = kNone; // outside, or not finite
        depth[static_cast<std::size_t>(d)] = std::min(below, above);
    }
    return depth;
}

} // namespace regolith::particles
