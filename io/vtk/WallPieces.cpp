#include "io/vtk/WallPieces.hpp"

#include "core/Error.hpp"
#include "io/vtk/VtkModule.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace regolith::io::detail {

namespace {

using core::Vec3;
using particles::Wall;
using particles::WallShape;

/// Appends one polygon through `corners` (in order round it) of wall `k`.
void addPolygon(WallMesh& m, Wall const& w, std::size_t k, std::vector<Vec3> const& corners) {
    if (corners.size() < 3)
        return;
    if (m.offsets.empty())
        m.offsets.push_back(0);
    for (Vec3 const& c : corners) {
        m.connectivity.push_back(static_cast<std::int64_t>(m.xyz.size() / 3));
        Vec3 const v = w.surfaceVelocity(c);
        m.xyz.insert(m.xyz.end(), {c.x(), c.y(), c.z()});
        m.velocity.insert(m.velocity.end(), {v.x(), v.y(), v.z()});
    }
    m.offsets.push_back(static_cast<std::int64_t>(m.connectivity.size()));
    m.wall.push_back(static_cast<std::int32_t>(k));
    m.type.push_back(static_cast<std::int32_t>(w.type));
}

/// The section of the plane through `p` with unit normal `n` and the box: where it crosses the
/// box's 12 edges, in order round the centroid (empty if it misses the box).
std::vector<Vec3> planeSection(Vec3 const& p, Vec3 const& n, core::AABB const& box) {
    std::vector<Vec3> hits;
    for (int axis = 0; axis < 3; ++axis) {
        int const a = (axis + 1) % 3, b = (axis + 2) % 3;
        for (int corner = 0; corner < 4; ++corner) {
            Vec3 lo = box.min;
            lo[a] = (corner & 1) ? box.max[a] : box.min[a];
            lo[b] = (corner & 2) ? box.max[b] : box.min[b];
            Vec3 hi = lo;
            hi[axis] = box.max[axis];
            double const dl = (lo - p).dot(n), dh = (hi - p).dot(n);
            bool const crosses = (dl <= 0.0 && dh >= 0.0) || (dl >= 0.0 && dh <= 0.0);
            if (!crosses || dl == dh) // an edge in the plane: its ends are other edges' hits
                continue;
            hits.push_back(lo + (dl / (dl - dh)) * (hi - lo));
        }
    }
    if (hits.size() < 3)
        return {};
    Vec3 centre = Vec3::Zero();
    for (Vec3 const& h : hits)
        centre += h;
    centre /= static_cast<double>(hits.size());
    Vec3 const u = particles::WallGeometry::anyPerpendicular(n), v = n.cross(u);
    auto angle = [&](Vec3 const& h) {
        return std::atan2((h - centre).dot(v), (h - centre).dot(u));
    };
    std::sort(hits.begin(), hits.end(),
              [&](Vec3 const& x, Vec3 const& y) { return angle(x) < angle(y); });
    // A corner of the box in the plane is the hit of three edges: keep one.
    std::vector<Vec3> out;
    double const tiny = 1e-12 * box.extent().norm();
    for (Vec3 const& h : hits)
        if (out.empty() || (h - out.back()).norm() > tiny)
            out.push_back(h);
    if (out.size() > 1 && (out.front() - out.back()).norm() <= tiny)
        out.pop_back();
    return out;
}

/// kCircleSides points round the circle of radius r about `centre` in the plane spanned by
/// the unit vectors u and v, starting at u.
std::vector<Vec3> circle(Vec3 const& centre, Vec3 const& u, Vec3 const& v, double r) {
    std::vector<Vec3> out;
    for (int s = 0; s < kCircleSides; ++s) {
        double const phi = 2.0 * std::numbers::pi * s / kCircleSides;
        out.push_back(centre + r * (std::cos(phi) * u + std::sin(phi) * v));
    }
    return out;
}

} // namespace

WallMesh wallMesh(particles::WallList const& walls, core::AABB const& domain) {
    WallMesh m;
    for (std::size_t k = 0; k < walls.size(); ++k) {
        Wall const& w = walls[k];
        particles::WallGeometry const& g = w.geometry;
        Vec3 const side = g.normal.cross(g.edge);
        switch (g.shape) {
        case WallShape::Plane:
            addPolygon(m, w, k, planeSection(g.point, g.normal, domain));
            break;
        case WallShape::Rectangle: {
            Vec3 const a = g.halfSize[0] * g.edge, b = g.halfSize[1] * side;
            addPolygon(m, w, k,
                       {g.point - a - b, g.point + a - b, g.point + a + b, g.point - a + b});
            break;
        }
        case WallShape::Disc:
            addPolygon(m, w, k, circle(g.point, g.edge, side, g.radius));
            break;
        case WallShape::Cylinder: {
            // Along the axis from the lowest to the highest corner of the box.
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (int c = 0; c < 8; ++c) {
                Vec3 const corner((c & 1) ? domain.max.x() : domain.min.x(),
                                  (c & 2) ? domain.max.y() : domain.min.y(),
                                  (c & 4) ? domain.max.z() : domain.min.z());
                double const t = (corner - g.point).dot(g.normal);
                lo = std::min(lo, t);
                hi = std::max(hi, t);
            }
            auto const ring = circle(g.point, g.edge, side, g.radius);
            for (int s = 0; s < kCircleSides; ++s) {
                Vec3 const& p = ring[static_cast<std::size_t>(s)];
                Vec3 const& q = ring[static_cast<std::size_t>((s + 1) % kCircleSides)];
                addPolygon(
                    m, w, k,
                    {p + lo * g.normal, q + lo * g.normal, q + hi * g.normal, p + hi * g.normal});
            }
            break;
        }
        }
    }
    return m;
}

void writeWallPiece(std::string const& path, WallMesh const& m) {
    std::vector<vtkxml::Column> const pointData{{{"velocity", "Float64", 3}, m.velocity.data()}};
    std::vector<vtkxml::Column> const cellData{{{"wall", "Int32", 1}, m.wall.data()},
                                               {{"type", "Int32", 1}, m.type.data()}};
    std::vector<std::int64_t> const offsets =
        m.offsets.empty() ? std::vector<std::int64_t>{0} : m.offsets;
    if (!vtkxml::module().writePolygons(path, m.xyz.size() / 3, m.xyz.data(), offsets,
                                        m.connectivity, pointData, cellData))
        throw core::Error(fmt::format("cannot write VTK file '{}'", path));
}

} // namespace regolith::io::detail
