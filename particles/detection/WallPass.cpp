/// ContactDetector's sphere-wall detection (the walls are global: each block tests its masters
/// at image zero against every wall): a branch-free screen of the copies against the plane
/// walls, then the exact test of the marked copies in storage order.
#include "particles/detection/ContactDetector.hpp"

#include <algorithm>
#include <array>
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
    for (Wall const& w : walls) {
        if (w.geometry.shape != WallShape::Plane) {
            std::fill_n(near.begin(), n, std::uint8_t{1}); // tested one by one
            return;
        }
    }
    double const* const x = ps.positions().data()->data();
    double const* const radius = ps.radii().data();
    std::uint8_t* const mark = near.data();
    // Up to kPlanes planes in one pass over the copies (each copy's centre loaded once); more
    // in further passes. WallGeometry::distance's operations, widened by a relative 1e-9 of
    // the coordinates (its rounding, contracted or not, lies far below it): never narrower
    // than the test.
    constexpr std::size_t kPlanes = 2;
    for (std::size_t first = 0; first < walls.size(); first += kPlanes) {
        std::array<double, 3 * kPlanes> point{}, normal{};
        std::array<double, kPlanes> scale{};
        std::size_t const planes = std::min(kPlanes, walls.size() - first);
        for (std::size_t w = 0; w < kPlanes; ++w) {
            // A missing second plane repeats the first: the same marks.
            WallGeometry const& g = walls[first + std::min(w, planes - 1)].geometry;
            for (int a = 0; a < 3; ++a) {
                point[3 * w + a] = g.point[a];
                normal[3 * w + a] = g.normal[a];
            }
            scale[w] = 1e-9 * (1.0 + g.point.cwiseAbs().maxCoeff());
        }
        for (std::size_t k = 0; k < n; ++k) {
            double const cx = x[3 * k], cy = x[3 * k + 1], cz = x[3 * k + 2];
            double const relative = 1e-9 * (std::abs(cx) + std::abs(cy) + std::abs(cz));
            std::uint8_t hit = 0;
            for (std::size_t w = 0; w < kPlanes; ++w) {
                double const d = (cx - point[3 * w]) * normal[3 * w] +
                                 (cy - point[3 * w + 1]) * normal[3 * w + 1] +
                                 (cz - point[3 * w + 2]) * normal[3 * w + 2];
                // Not finite: marked, and the exact test drops it as before.
                hit |= !(d >= radius[k] + (scale[w] + relative)) ? 1 : 0;
            }
            mark[k] |= hit;
        }
    }
}

} // namespace regolith::particles
