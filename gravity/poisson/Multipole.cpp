#include "gravity/poisson/Multipole.hpp"

#include <array>
#include <span>

namespace regolith::gravity {

std::vector<double> occupiedCells(CellField const& density) {
    std::vector<double> out;
    forEachOccupiedCell(density, [&](core::Vec3 const& x, double m) {
        out.insert(out.end(), {x[0], x[1], x[2], m});
    });
    return out;
}

MassMoments massMoments(core::Comm const& comm, std::span<double const> cells,
                        core::Vec3 const& origin) {
    // Moments about `origin`, which keeps the numbers small (no cancellation of huge second
    // moments far from the origin).
    std::array<double, 11> s{}; // M, M x (3), M x x^T (xx, yy, zz, xy, xz, yz), count
    for (std::size_t c = 0; c + 3 < cells.size(); c += 4) {
        double const m = cells[c + 3];
        core::Vec3 const x = core::Vec3(cells[c], cells[c + 1], cells[c + 2]) - origin;
        s[0] += m;
        for (int a = 0; a < 3; ++a)
            s[1 + static_cast<std::size_t>(a)] += m * x[a];
        s[4] += m * x[0] * x[0];
        s[5] += m * x[1] * x[1];
        s[6] += m * x[2] * x[2];
        s[7] += m * x[0] * x[1];
        s[8] += m * x[0] * x[2];
        s[9] += m * x[1] * x[2];
        s[10] += 1.0;
    }
    comm.allReduceInPlace(std::span<double>(s), core::ReduceOp::Sum);
    MassMoments out;
    out.mass = s[0];
    out.occupiedCells = s[10];
    if (out.mass <= 0.0) {
        out.centre = origin;
        return out;
    }
    core::Vec3 const c{s[1] / s[0], s[2] / s[0], s[3] / s[0]};
    Eigen::Matrix3d second;
    second << s[4], s[7], s[8], s[7], s[5], s[9], s[8], s[9], s[6];
    second -= out.mass * c * c.transpose(); // about the centre of mass
    out.centre = origin + c;
    out.quadrupole = 3.0 * second - second.trace() * Eigen::Matrix3d::Identity();
    return out;
}

double multipolePotential(MassMoments const& m, double G, core::Vec3 const& x) {
    core::Vec3 const d = x - m.centre;
    double const r2 = d.squaredNorm();
    double const r = std::sqrt(r2);
    return -G * (m.mass / r + 0.5 * d.dot(m.quadrupole * d) / (r2 * r2 * r));
}

} // namespace regolith::gravity
