/// ContactDetector's sphere-wall detection (the walls are global: each block tests its masters
/// at image zero against every wall): a branch-free screen of the copies against the plane
/// walls, then the exact test of the marked copies in storage order.
#include "particles/detection/ContactDetector.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>

namespace regolith::particles {

namespace {

/// wallPass's exact test of copy k against `walls` (none unless a master at image zero, not
/// Fixed): appends its wall contacts to `out`, counting them in `stats`.
void wallContactsOf(ParticleStorage const& ps, std::size_t k, std::span<Wall const> walls,
                    DetectorStats& stats, ContactList& out) {
    Flags const flags = ps.flags(k);
    if (flags.isFixed())
        return; // a fixed grain takes no force, and a wall none either
    if (!flags.isMaster() || !isZero(ps.image(k)))
        return; // the master, in exactly one block, evaluates the sphere's wall contacts
    core::Vec3 const& x = ps.position(k);
    double const r = ps.radius(k);
    for (std::size_t w = 0; w < walls.size(); ++w) {
        WallGeometry const& surface = walls[w].geometry;
        double const delta = r - surface.distance(x);
        if (!(delta > 0.0))
            continue;
        WallTouch const touch = surface.touch(x);
        ++stats.overlapsFound;
        core::Vec3 const p = x - (r - 0.5 * delta) * touch.normal;
        out.walls.push_back(WallContact{k, w, p, touch.normal, delta});
    }
}

} // namespace

void ContactDetector::wallPass(ParticleStorage const& ps, WallList const& walls, ContactList& out) {
    if (walls.empty())
        return;
    // A local view: its size is not reloaded after every push_back below.
    std::span<Wall const> const all(walls.begin(), walls.end());
    std::size_t const n = ps.size();
    // The copies a plane might touch, screened without a branch per copy (most copies of a
    // scene touch no wall); the exact test below decides, copy by copy in storage order,
    // visiting the marks eight at a time (each 0 or 1; padded to a multiple of eight).
    m_nearWall.assign((n + 7) / 8 * 8, 0);
    screenPlaneWalls(ps, all, m_nearWall);
    for (std::size_t first = 0; first < n; first += 8) {
        std::uint64_t marks = 0;
        std::memcpy(&marks, &m_nearWall[first], sizeof marks);
        for (; marks != 0; marks &= marks - 1)
            wallContactsOf(ps, first + static_cast<std::size_t>(std::countr_zero(marks)) / 8, all,
                           m_stats, out);
    }
}

void ContactDetector::screenPlaneWalls(ParticleStorage const& ps, std::span<Wall const> walls,
                                       std::vector<std::uint8_t>& near) {
    std::size_t const n = ps.size();
    double const* const x = ps.positions().data()->data();
    double const* const radius = ps.radii().data();
    std::uint8_t* const mark = near.data();
    for (Wall const& w : walls) {
        if (w.geometry.shape != WallShape::Plane) {
            std::fill_n(near.begin(), n, std::uint8_t{1}); // tested one by one
            return;
        }
        // WallGeometry::distance's operations, widened by a relative 1e-9 of the coordinates
        // (its rounding, contracted or not, lies far below it): never narrower than the test.
        core::Vec3 const p = w.geometry.point, u = w.geometry.normal;
        double const scale = 1e-9 * (1.0 + p.cwiseAbs().maxCoeff());
        for (std::size_t k = 0; k < n; ++k) {
            double const d = (x[3 * k] - p.x()) * u.x() + (x[3 * k + 1] - p.y()) * u.y() +
                             (x[3 * k + 2] - p.z()) * u.z();
            double const slack = scale + 1e-9 * (std::abs(x[3 * k]) + std::abs(x[3 * k + 1]) +
                                                 std::abs(x[3 * k + 2]));
            // Not finite: marked, and the exact test drops it as before.
            mark[k] |= !(d >= radius[k] + slack) ? 1 : 0;
        }
    }
}

} // namespace regolith::particles
