#pragma once
/// What contact detection produces and the contact models consume.
#include "core/math/Vec3.hpp"

#include <cstddef>
#include <vector>

namespace regolith::particles {

/// Two overlapping spheres. `i` and `j` are storage indices in canonical order:
/// uid(i) < uid(j), so the pair and its history key do not depend on where it was found.
struct Contact {
    std::size_t i = 0;
    std::size_t j = 0;
    /// Middle of the overlap: x_i + (r_i - penetration / 2) * normal [length].
    core::Vec3 point = core::Vec3::Zero();
    /// Unit vector from the centre of i towards the centre of j.
    core::Vec3 normal = core::Vec3::UnitZ();
    /// r_i + r_j - |x_j - x_i| > 0 [length].
    double penetration = 0.0;
};

/// A sphere overlapping a wall; the wall plays the role of `i` (infinite mass, at rest).
struct WallContact {
    std::size_t particle = 0; ///< storage index of the sphere
    std::size_t wall = 0;     ///< index into the WallList
    /// Middle of the overlap: x - (r - penetration / 2) * normal [length].
    core::Vec3 point = core::Vec3::Zero();
    /// The wall's outward normal: from the wall towards the sphere.
    core::Vec3 normal = core::Vec3::UnitZ();
    /// r - (signed distance of the centre from the wall) > 0 [length].
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
