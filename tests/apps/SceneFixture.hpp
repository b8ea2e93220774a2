#pragma once
// The scene the scene-section tests start from: valid, every section used; each test breaks it
// one key at a time with --set (parse, errorWith).
#include "apps/regolith/SceneSections.hpp"
#include "core/Error.hpp"
#include "core/config/ConfigFile.hpp"

#include <initializer_list>
#include <string>
#include <string_view>

namespace regolith::apps::test {

// A valid scene using every section; the tests break it one key at a time with --set.
inline constexpr char const* kScene = R"([domain]
min = [0, 0, 0]
max = [8, 8, 4]
blocks = [2, 2, 1]
periodic = [false, false, false]
refine = [{ min = [0, 0, 0], max = [2, 2, 2], level = 1 }]
cells_per_block = [8, 8, 8]
[time]
dt = 0.01
steps = 10
[sync]
method = "sos"
[contact]
model = "hertz"
youngs_modulus = 1.82e7
poisson_ratio = 0.3
restitution = 0.5
friction = 0.3
rolling_friction = 0.01
[gravity]
external = [0, 0, -9.81]
self = "tree"
G = 1.0
theta = 0.7
update_threshold = 0.1
softening = 0.01
[gravity.petsc]
options = "-pc_type gamg"
[[particles]]
kind = "lattice"
lattice = "hcp"
spacing = 1.0
radius = 0.5
density = 2.0
velocity = { random = [-0.1, 0.1], seed = 7 }
[[particles]]
kind = "list"
radius = [1.0, 2.0]
position = [[1, 1, 1], [5, 5, 2]]
density = 3.0
[[particles]]
kind = "agglomerate"
center = [4, 4, 2]
radius = 1.5
grain_radius = [0.1, 0.2]
count = 100
velocity = [0, 1, 0]
density = 3000.0
seed = 3
[[particles]]
kind = "file"
path = "initial.csv"
density = 2.5
type = 2
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 2]
type = 1
[output]
dir = "results"
vtk_every = 10
checkpoint_every = 100
)";

inline SceneDescription parse(std::initializer_list<std::string_view> overrides = {}) {
    auto root = core::ConfigTable::fromString(kScene, "scenes/s.toml");
    for (auto const o : overrides)
        root.applyOverride(o);
    return apps::parseScene(root, "scenes/s.toml");
}

/// The InputError message for the scene with `override` applied.
inline std::string errorWith(std::initializer_list<std::string_view> overrides);
inline std::string errorWith(std::string_view override) {
    return errorWith({override});
}
inline std::string errorWith(std::initializer_list<std::string_view> overrides) {
    try {
        (void)parse(overrides);
    } catch (core::InputError const& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace regolith::apps::test
