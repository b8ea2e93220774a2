#include "gravity/baselines/NodeGrid.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace regolith::gravity::baselines {

namespace {

constexpr std::int64_t kBias = std::int64_t{1} << 20; ///< indices in [-2^20, 2^20)

std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) {
    auto const u = [](std::int64_t v) { return static_cast<std::uint64_t>(v + kBias); };
    return (u(i) << 42) | (u(j) << 21) | u(k);
}

std::array<std::int64_t, 3> unkey(std::uint64_t key) {
    constexpr std::uint64_t mask = (std::uint64_t{1} << 21) - 1;
    return {static_cast<std::int64_t>((key >> 42) & mask) - kBias,
            static_cast<std::int64_t>((key >> 21) & mask) - kBias,
            static_cast<std::int64_t>(key & mask) - kBias};
}

/// Cell index of p and the fractional position inside the cell.
std::array<std::int64_t, 3> cellOf(NodeGrid const& g, double x, double y, double z,
                                   std::array<double, 3>& frac) {
    double const s[3] = {(x - g.origin.x()) / g.spacing, (y - g.origin.y()) / g.spacing,
                         (z - g.origin.z()) / g.spacing};
    std::array<std::int64_t, 3> c{};
    for (std::size_t a = 0; a < 3; ++a) {
        double const f = std::floor(s[a]);
        if (!(std::abs(f) < static_cast<double>(kBias - 4)))
            throw core::InputError(fmt::format(
                "gravity.grid_spacing = {}: a grain lies {} nodes from the origin, beyond "
                "the grid's index range",
                g.spacing, f));
        c[a] = static_cast<std::int64_t>(f);
        frac[a] = s[a] - f;
    }
    return c;
}

} // namespace

void validate(NodeGrid const& grid) {
    if (!(grid.spacing > 0.0) || !std::isfinite(grid.spacing))
        throw core::InputError(fmt::format(
            "gravity.grid_spacing = {}: the node spacing must be finite and > 0 m", grid.spacing));
}

std::vector<std::uint64_t> nodesAround(NodeGrid const& grid, PointMasses const& grains,
                                       bool expand64) {
    std::vector<std::uint64_t> keys;
    std::int64_t const lo = expand64 ? -1 : 0;
    std::int64_t const hi = expand64 ? 2 : 1;
    std::vector<std::uint64_t> cells;
    cells.reserve(grains.size());
    std::array<double, 3> frac{};
    for (std::size_t i = 0; i < grains.size(); ++i) {
        auto const c = cellOf(grid, grains.x[i], grains.y[i], grains.z[i], frac);
        cells.push_back(key(c[0], c[1], c[2]));
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    for (std::uint64_t const ck : cells) {
        auto const c = unkey(ck);
        for (std::int64_t i = lo; i <= hi; ++i)
            for (std::int64_t j = lo; j <= hi; ++j)
                for (std::int64_t k = lo; k <= hi; ++k)
                    keys.push_back(key(c[0] + i, c[1] + j, c[2] + k));
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    return keys;
}

core::Vec3 nodePosition(NodeGrid const& grid, std::uint64_t k) {
    auto const c = unkey(k);
    return grid.origin + grid.spacing * core::Vec3(static_cast<double>(c[0]),
                                                   static_cast<double>(c[1]),
                                                   static_cast<double>(c[2]));
}

double interpolateToGrains(NodeGrid const& grid, NodeField const& nodes, PointMasses const& targets,
                           double G, FieldOut out) {
    validateFieldOut(out, targets.size());
    double energy = 0.0;
    std::array<double, 3> t{};
    for (std::size_t i = 0; i < targets.size(); ++i) {
        auto const c = cellOf(grid, targets.x[i], targets.y[i], targets.z[i], t);
        double a[4] = {0, 0, 0, 0};
        // The target's own field at the 8 corners.
        std::array<double, 8> cx{}, cy{}, cz{}, sx{}, sy{}, sz{}, sphi{};
        for (int corner = 0; corner < 8; ++corner) {
            core::Vec3 const p = nodePosition(
                grid, key(c[0] + (corner & 1), c[1] + ((corner >> 1) & 1), c[2] + (corner >> 2)));
            cx[static_cast<std::size_t>(corner)] = p.x();
            cy[static_cast<std::size_t>(corner)] = p.y();
            cz[static_cast<std::size_t>(corner)] = p.z();
        }
        accumulateSphereField(cx.data(), cy.data(), cz.data(), 8, targets, i, i + 1, G, sx.data(),
                              sy.data(), sz.data(), sphi.data());
        for (int corner = 0; corner < 8; ++corner) {
            int const di = corner & 1;
            int const dj = (corner >> 1) & 1;
            int const dk = (corner >> 2) & 1;
            double const w = (di != 0 ? t[0] : 1.0 - t[0]) * (dj != 0 ? t[1] : 1.0 - t[1]) *
                             (dk != 0 ? t[2] : 1.0 - t[2]);
            std::uint64_t const k = key(c[0] + di, c[1] + dj, c[2] + dk);
            auto const it = std::lower_bound(nodes.keys.begin(), nodes.keys.end(), k);
            if (it == nodes.keys.end() || *it != k)
                throw core::Error("gravity grid: a grain's cell corner has no node value");
            auto const n = static_cast<std::size_t>(it - nodes.keys.begin());
            auto const s = static_cast<std::size_t>(corner);
            a[0] += w * (nodes.ax[n] - sx[s]);
            a[1] += w * (nodes.ay[n] - sy[s]);
            a[2] += w * (nodes.az[n] - sz[s]);
            a[3] += w * (nodes.phi[n] - sphi[s]);
        }
        out.ax[i] = a[0];
        out.ay[i] = a[1];
        out.az[i] = a[2];
        if (!out.phi.empty())
            out.phi[i] = a[3];
        energy += 0.5 * targets.m[i] * a[3];
    }
    return energy;
}

void accumulateSphereField(double const* px, double const* py, double const* pz, std::size_t n,
                           PointMasses const& s, std::size_t begin, std::size_t end, double G,
                           double* ax, double* ay, double* az, double* phi) {
    bool const radii = !s.r.empty();
    for (std::size_t j = begin; j < end; ++j) {
        double const xj = s.x[j];
        double const yj = s.y[j];
        double const zj = s.z[j];
        double const gm = G * s.m[j];
        double const rj = radii ? s.r[j] : 0.0;
        double const rj2 = rj * rj;
        double const invR = rj > 0.0 ? 1.0 / rj : 0.0;
        double const invR3 = invR * invR * invR;
        for (std::size_t i = 0; i < n; ++i) {
            double const dx = xj - px[i];
            double const dy = yj - py[i];
            double const dz = zj - pz[i];
            double const d2 = dx * dx + dy * dy + dz * dz;
            bool const inside = d2 < rj2;
            bool const valid = d2 > 0.0;
            double const inv = valid ? 1.0 / std::sqrt(d2) : 0.0;
            double const f = inside ? gm * invR3 : gm * inv * inv * inv;
            double const p = inside ? gm * 0.5 * (3.0 * rj2 - d2) * invR3 : gm * inv;
            ax[i] += f * dx;
            ay[i] += f * dy;
            az[i] += f * dz;
            phi[i] -= p;
        }
    }
}

} // namespace regolith::gravity::baselines
