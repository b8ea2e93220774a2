#pragma once
/// How deep each copy of a Verlet list stood inside the box where the contact-point rule emits
/// (emittingBox), measured once per rebuild and id: a pair of two copies deeper than its
/// ownership reach is settled without its midpoint (ContactDetector's settlePair), and one
/// deeper than the list's motion keeps its spring (settledMode). Measured per axis: the list's
/// shifts since the rebuild count against the depth along the axis they moved on (docs/sync.md,
/// "A list follows a drift"), so a pack sliding along x keeps its depths from the y and z faces.
#include "core/math/AABB.hpp"
#include "core/math/Vec3.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/detection/VerletList.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <algorithm>
#include <array>
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
    /// Depths along x, y and z: from the nearer of the box's two faces on each axis.
    using Axes = std::array<double, 3>;
    /// The list's shifts moved every reference by at most shifted[a] along axis a since
    /// start().
    void setShifted(core::Vec3 const& shifted) { m_shifted = shifted; }
    [[nodiscard]] core::Vec3 const& shifted() const { return m_shifted; }
    [[nodiscard]] bool unshifted() const { return m_shifted.isZero(); }
    /// How deep the reference of `id` (where it stood at the rebuild) lies inside the box
    /// along each axis, measured the first time it is asked: 0 on every axis outside it, if not
    /// finite, for a dead id or an arrival (the full rule decides those).
    [[nodiscard]] Axes const& ofAxes(VerletList const& list, ParticleStorage const& ps,
                                     VerletList::Id id) const {
        if (id < m_depth.size() && m_depth[id][0] != kUnmeasured)
            return m_depth[id]; // (each id is asked for by every pair it is in)
        return measure(list, ps, id);
    }
    /// The depth of `id` inside the box: the least along the three axes.
    [[nodiscard]] double of(VerletList const& list, ParticleStorage const& ps,
                            VerletList::Id id) const {
        Axes const& d = ofAxes(list, ps, id);
        return std::min({d[0], d[1], d[2]});
    }
    /// Whether ids a and b both lie deeper than `depth` now, the shifts since the rebuild
    /// counted on each axis.
    [[nodiscard]] bool deeperThan(VerletList const& list, ParticleStorage const& ps,
                                  VerletList::Id a, VerletList::Id b, double depth) const {
        Axes const& da = ofAxes(list, ps, a);
        Axes const& db = ofAxes(list, ps, b);
        bool deeper = true;
        for (int d = 0; d < 3; ++d) {
            double const need = depth + m_shifted[d];
            auto const u = static_cast<std::size_t>(d);
            deeper = deeper && da[u] > need && db[u] > need;
        }
        return deeper;
    }
    [[nodiscard]] std::size_t bytes() const { return m_depth.capacity() * sizeof(Axes); }

private:
    static constexpr double kUnmeasured = -1.0;
    /// ofAxes() the first time `id` is asked for.
    [[nodiscard]] Axes const& measure(VerletList const& list, ParticleStorage const& ps,
                                      VerletList::Id id) const;
    core::AABB m_emits;
    core::Vec3 m_period = core::Vec3::Zero();
    core::Vec3 m_shifted = core::Vec3::Zero();
    mutable std::vector<Axes> m_depth; ///< per id of the rebuild: a cache
};

} // namespace regolith::particles
