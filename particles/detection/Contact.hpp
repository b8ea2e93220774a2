#pragma once
/// What contact detection produces and the contact models consume.
#include "core/math/Vec3.hpp"

#include <cstddef>
#include <vector>

namespace regolith::particles {

/// Two overlapping spheres. `i` and `j` are storage indices in canonical order:
/// uid(i) < uid(j), so the pair and its history key do not depend on where it was found.
///
/// Frames. Every stored copy keeps its master's canonical position (CopyImage.hpp), so the
/// geometry is expressed in i's CANONICAL frame: j's centre there is
/// `position(j) + shiftJ`, with shiftJ = imageOffset(image(j) - image(i), period) (zero
/// without periodic images). Only the image difference enters, so every block that sees the
/// pair computes the same bits.
struct Contact {
    std::size_t i = 0;
    std::size_t j = 0;
    /// Middle of the overlap in i's canonical frame: x_i + (r_i - penetration / 2) * normal
    /// [length].
    core::Vec3 point = core::Vec3::Zero();
    /// Unit vector from the centre of i towards the centre of j (+ shiftJ).
    core::Vec3 normal = core::Vec3::UnitZ();
    /// r_i + r_j - |x_j + shiftJ - x_i| > 0 [length].
    double penetration = 0.0;
    /// Added to j's stored (canonical) position gives j in i's frame [length].
    core::Vec3 shiftJ = core::Vec3::Zero();
};

/// Two overlapping spheres (i, j, shiftJ as in Contact) without the rest of their geometry:
/// what the fused contact loop hands to a consumer that computes normal, penetration and point
/// itself, with the bits of overlapGeometry (PairRule.hpp), in its own vector lanes
/// (SpringDashpotBatch), rather than having them written to a Contact and read back.
struct PairOverlap {
    std::size_t i = 0;
    std::size_t j = 0;
    core::Vec3 shiftJ = core::Vec3::Zero();

    /// The pair of a contact found with its geometry.
    [[nodiscard]] static PairOverlap of(Contact const& c) { return {c.i, c.j, c.shiftJ}; }
};

/// A sphere overlapping a wall; the wall plays the role of `i` (infinite mass, moved by its
/// motion).
struct WallContact {
    std::size_t particle = 0; ///< storage index of the sphere
    std::size_t wall = 0;     ///< index into the WallList
    /// Middle of the overlap, in the sphere's canonical frame (walls are not periodic):
    /// x - (r - penetration / 2) * normal [length].
    core::Vec3 point = core::Vec3::Zero();
    /// From the wall's nearest point towards the sphere (WallTouch::normal).
    core::Vec3 normal = core::Vec3::UnitZ();
    /// r - (signed distance of the centre from the wall surface) > 0 [length].
    double penetration = 0.0;
};

/// All contacts one block evaluates in one step.
struct ContactList {
    std::vector<Contact> pairs;
    std::vector<WallContact> walls;

    void clear() {
        pairs.clear();
        walls.clear();
    }
    [[nodiscard]] std::size_t size() const { return pairs.size() + walls.size(); }
};

} // namespace regolith::particles
