#pragma once
// Helpers of the periodic detection and evaluation tests: bitwise comparison, block tilings of
// a periodic domain with the forest's exact faces, and the copies a block holds, found by
// brute force.
#include "core/math/AABB.hpp"
#include "domain/BlockId.hpp"
#include "domain/ForestGeometry.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace regolith::particles::test {

using core::AABB;
using core::Vec3;

inline bool sameBits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
inline bool sameBits(Vec3 const& a, Vec3 const& b) {
    return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}
/// Point, normal, penetration and shiftJ bit for bit (the indices are per block).
inline bool sameBits(Contact const& a, Contact const& b) {
    return sameBits(a.point, b.point) && sameBits(a.normal, b.normal) &&
           sameBits(a.penetration, b.penetration) && sameBits(a.shiftJ, b.shiftJ);
}

/// Blocks of `n` root blocks per axis tiling `domain`, with the forest's exact faces.
struct Tiling {
    PeriodicFrame frame;
    std::vector<AABB> boxes;
};

inline Tiling tile(AABB const& domain, std::array<bool, 3> periodic, std::array<int, 3> n) {
    regolith::domain::ForestGeometry const geometry(domain, n, periodic, 0);
    Tiling t{PeriodicFrame(geometry), {}};
    for (std::uint64_t r = 0; r < geometry.rootCount(); ++r)
        t.boxes.push_back(geometry.box(regolith::domain::BlockId::root(r)));
    return t;
}

/// The images a copy can have: {-1, 0, 1} on periodic axes, 0 elsewhere.
inline std::vector<CopyImage> images(PeriodicFrame const& frame) {
    std::vector<CopyImage> out;
    auto range = [&](std::size_t a) { return frame.periodic[a] ? 1 : 0; };
    for (int x = -range(0); x <= range(0); ++x)
        for (int y = -range(1); y <= range(1); ++y)
            for (int z = -range(2); z <= range(2); ++z)
                out.push_back(CopyImage{static_cast<std::int8_t>(x), static_cast<std::int8_t>(y),
                                        static_cast<std::int8_t>(z)});
    return out;
}

/// What a block with `box` holds of `bodies` (canonical states inside the domain), found by
/// brute force: copy (uid, k) iff the ball at x + k * period reaches into the box (with the
/// synchronisation's relative margin 1e-9); the master is the image-0 copy in the block that
/// contains x, every other copy a shadow.
inline ParticleStorage blockCopies(std::vector<ParticleInit> const& bodies, AABB const& box,
                                   PeriodicFrame const& frame) {
    ParticleStorage ps;
    Vec3 const period = frame.period();
    for (ParticleInit const& b : bodies)
        for (CopyImage const& k : images(frame)) {
            Vec3 const local = localPosition(b.position, k, period);
            double const reach = b.radius * (1.0 + 1e-9);
            if (!(box.sqDistance(local) < reach * reach))
                continue;
            ParticleInit copy = b;
            copy.image = k;
            if (!(isZero(k) && box.contains(b.position)))
                copy.flags = copy.flags | Flag::Shadow;
            ps.add(copy);
        }
    return ps;
}

} // namespace regolith::particles::test
