#include "gravity/samples/SyntheticBodies.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <unordered_map>

namespace regolith::gravity::samples {

void Body::push(Body const& other, std::size_t i) {
    x.push_back(other.x[i]);
    y.push_back(other.y[i]);
    z.push_back(other.z[i]);
    m.push_back(other.m[i]);
    r.push_back(other.r[i]);
}

namespace {

core::Vec3 unitVector(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (;;) {
        core::Vec3 const v(u(rng), u(rng), u(rng));
        double const n2 = v.squaredNorm();
        if (n2 > 1e-6 && n2 <= 1.0)
            return v / std::sqrt(n2);
    }
}

/// Uniform hash grid of cell `h` for the overlap test of the packer.
class SphereHash {
public:
    explicit SphereHash(double h)
        : m_h(h) {}

    void insert(core::Vec3 const& p, std::size_t id) { m_cells[key(cell(p))].push_back(id); }

    /// Does a sphere (p, r) overlap any stored grain (centres cx.., radii rr)?
    [[nodiscard]] bool overlaps(core::Vec3 const& p, double r, Body const& b) const {
        auto const c = cell(p);
        for (long dx = -1; dx <= 1; ++dx)
            for (long dy = -1; dy <= 1; ++dy)
                for (long dz = -1; dz <= 1; ++dz) {
                    auto const it = m_cells.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
                    if (it == m_cells.end())
                        continue;
                    for (std::size_t const j : it->second) {
                        double const d = r + b.r[j];
                        core::Vec3 const q(b.x[j], b.y[j], b.z[j]);
                        if ((q - p).squaredNorm() < d * d)
                            return true;
                    }
                }
        return false;
    }

private:
    [[nodiscard]] std::array<long, 3> cell(core::Vec3 const& p) const {
        return {static_cast<long>(std::floor(p.x() / m_h)),
                static_cast<long>(std::floor(p.y() / m_h)),
                static_cast<long>(std::floor(p.z() / m_h))};
    }
    static std::uint64_t key(std::array<long, 3> const& c) {
        auto const u = [](long v) { return static_cast<std::uint64_t>(v + (1L << 20)); };
        return (u(c[0]) << 42) | (u(c[1]) << 21) | u(c[2]);
    }

    double m_h;
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> m_cells;
};

} // namespace

Body plummerSphere(std::size_t n, double totalMass, double a, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    // M(r)/M = X  <=>  r = a / sqrt(X^{-2/3} - 1); X < 0.985 keeps r below ~10 a.
    constexpr double kMaxFraction = 0.985;
    Body b;
    double const mass = totalMass / static_cast<double>(n);
    for (std::size_t i = 0; i < n; ++i) {
        double const xFrac = kMaxFraction * std::max(u(rng), 1e-12);
        double const rad = a / std::sqrt(std::pow(xFrac, -2.0 / 3.0) - 1.0);
        core::Vec3 const p = rad * unitVector(rng);
        b.x.push_back(p.x());
        b.y.push_back(p.y());
        b.z.push_back(p.z());
        b.m.push_back(mass);
        b.r.push_back(0.0);
    }
    return b;
}

Body packedAgglomerate(std::size_t n, double rMin, double rMax, double density, double packing,
                       core::Vec3 const& centre, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> radiusDist(rMin, rMax);
    std::vector<double> radii(n);
    for (double& r : radii)
        r = radiusDist(rng);
    std::sort(radii.begin(), radii.end(), std::greater<>());
    double const sumR3 = std::accumulate(radii.begin(), radii.end(), 0.0,
                                         [](double s, double r) { return s + r * r * r; });
    double const bodyRadius = std::cbrt(sumR3 / packing);
    SphereHash hash(2.0 * rMax);
    Body b;
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    constexpr int kMaxAttempts = 100000;
    for (std::size_t i = 0; i < n; ++i) {
        double const r = radii[i];
        bool placed = false;
        for (int attempt = 0; attempt < kMaxAttempts && !placed; ++attempt) {
            core::Vec3 const q(u(rng), u(rng), u(rng));
            if (q.squaredNorm() > 1.0)
                continue;
            core::Vec3 const p = centre + (bodyRadius - r) * q;
            if (hash.overlaps(p, r, b))
                continue;
            hash.insert(p, b.size());
            b.x.push_back(p.x());
            b.y.push_back(p.y());
            b.z.push_back(p.z());
            b.r.push_back(r);
            b.m.push_back(density * 4.0 / 3.0 * std::numbers::pi * r * r * r);
            placed = true;
        }
        if (!placed)
            throw core::InputError(
                fmt::format("agglomerate: grain {} of {} (radius {}) found no place at packing "
                            "fraction {}",
                            i, n, r, packing));
    }
    return b;
}

Body slabOf(Body const& body, int part, int parts) {
    std::vector<std::size_t> order(body.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t c) { return body.x[a] < body.x[c]; });
    auto const n = body.size();
    auto const p = static_cast<std::size_t>(parts);
    auto const k = static_cast<std::size_t>(part);
    Body out;
    for (std::size_t i = k * n / p; i < (k + 1) * n / p; ++i)
        out.push(body, order[i]);
    return out;
}

} // namespace regolith::gravity::samples
