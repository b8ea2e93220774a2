#pragma once
/// Mass-assignment kernels of the particle-mesh method (Hockney & Eastwood, "Computer
/// Simulation Using Particles", ch. 5): cloud-in-cell (CIC, linear, 2 cells per axis) and
/// triangular-shaped cloud (TSC, quadratic, 3 cells per axis), as pure point functions, and
/// the sampling of a grain's ball by equal-weight points so that a grain larger than a cell
/// spreads its mass over the cells it covers. Interpolation uses the same weights, which is
/// what makes the self-force of a lone grain vanish (up to boundary effects).
#include "core/math/Vec3.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

namespace regolith::gravity {

enum class Assignment { Cic, Tsc };

/// "cic" / "tsc": the spelling of the kernel in scene files and messages.
[[nodiscard]] inline char const* toString(Assignment a) {
    return a == Assignment::Cic ? "cic" : "tsc";
}

/// Weights of one axis: cells first .. first + count - 1.
struct Stencil1D {
    std::int64_t first = 0;
    int count = 0;
    std::array<double, 3> w{};
};

/// The 1-D weights for a point at continuous cell coordinate u (cell centres at integers).
/// The weights are >= 0 and sum to 1 (to round-off).
[[nodiscard]] inline Stencil1D stencil(Assignment a, double u) {
    Stencil1D s;
    if (a == Assignment::Cic) {
        double const f = std::floor(u);
        double const d = u - f;
        s.first = static_cast<std::int64_t>(f);
        s.count = 2;
        s.w = {1.0 - d, d, 0.0};
    } else {
        double const c = std::floor(u + 0.5); // nearest centre
        double const d = u - c;               // in [-1/2, 1/2)
        s.first = static_cast<std::int64_t>(c) - 1;
        s.count = 3;
        s.w = {0.5 * (0.5 - d) * (0.5 - d), 0.75 - d * d, 0.5 * (0.5 + d) * (0.5 + d)};
    }
    return s;
}

/// Half-width of the kernel support in cells (a point at cell centre touches cells up to
/// this far): 1 for both CIC and TSC (TSC reaches 1.5 cells from the point).
[[nodiscard]] inline double supportCells(Assignment a) {
    return a == Assignment::Cic ? 1.0 : 1.5;
}

/// Offsets from the grain centre of the equal-weight points that represent a ball of radius
/// r on cells of size h: one point (the centre) if r <= min(h) / 2, else the points of a
/// cubic lattice of m^3 sites (m = ceil(2 r / min(h)), spacing 2r/m <= min(h), placed
/// symmetrically about the centre) that lie inside the ball. The symmetry keeps the samples'
/// centre of mass at the grain centre. Replaces `out`.
inline void ballSamples(double r, core::Vec3 const& h, std::vector<core::Vec3>& out) {
    out.clear();
    double const hMin = h.minCoeff();
    if (!(r > 0.5 * hMin)) {
        out.push_back(core::Vec3::Zero());
        return;
    }
    int const m = static_cast<int>(std::ceil(2.0 * r / hMin));
    double const s = 2.0 * r / m;
    for (int k = 0; k < m; ++k)
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i) {
                core::Vec3 const p{(i + 0.5) * s - r, (j + 0.5) * s - r, (k + 0.5) * s - r};
                if (p.squaredNorm() <= r * r)
                    out.push_back(p);
            }
}

} // namespace regolith::gravity
