#pragma once
/// How deep each copy of a Verlet list stood inside the box where the contact-point rule emits
/// (emittingBox), measured once per rebuild and id: a pair of two copies deeper than its
/// ownership reach is settled without its midpoint (ContactDetector's settlePair), and one
/// deeper than the list's motion keeps its spring (settledMode). The list's shifts since the
/// rebuild count against every depth (docs/sync.md, "A list follows a drift").
#include "core/math/AABB.hpp"
#include "core/math/Vec3.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/detection/VerletList.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <cstddef>
#include <vector>

namespace regolith::particles {

class ReferenceDepths {
public:
    /// At a rebuild of `list`: the box where `region` emits in `frame`, no depth measured yet,
    /// no shift.
    void start(VerletList const& list, core::AABB const& region, PeriodicFrame const& frame);
    /// No depth for any id (a list rebuilt empty: the ids its arrivals get have none).
    void clear();
    /// The list's shifts moved every reference by at most `shifted` along each axis since
    /// start().
    void setShifted(double shifted) { m_shifted = shifted; }
    [[nodiscard]] double shifted() const { return m_shifted; }
    /// How deep the reference of `id` (where it stood at the rebuild) lies inside the box,
    /// measured the first time it is asked: 0 outside it, if not finite, for a dead id or an
    /// arrival (the full rule decides those).
    [[nodiscard]] double of(VerletList const& list, ParticleStorage const& ps,
                            VerletList::Id id) const {
        if (id < m_depth.size() && m_depth[id] != kUnmeasured)
            return m_depth[id]; // (each id is asked for by every pair it is in)
        return measure(list, ps, id);
    }
    /// Whether ids a and b both lie deeper than `depth`, the shifts since the rebuild counted.
    [[nodiscard]] bool deeperThan(VerletList const& list, ParticleStorage const& ps,
                                  VerletList::Id a, VerletList::Id b, double depth) const {
        depth += m_shifted;
        return of(list, ps, a) > depth && of(list, ps, b) > depth;
    }
    [[nodiscard]] std::size_t bytes() const { return m_depth.capacity() * sizeof(double); }

private:
    static constexpr double kUnmeasured = -1.0;
    /// of() the first time `id` is asked for.
    [[nodiscard]] double measure(VerletList const& list, ParticleStorage const& ps,
                                 VerletList::Id id) const;
    core::AABB m_emits;
    core::Vec3 m_period = core::Vec3::Zero();
    double m_shifted = 0.0;
    mutable std::vector<double> m_depth; ///< per id of the rebuild: a cache
};

} // namespace regolith::particles
