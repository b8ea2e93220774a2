// regolith: the generic scene driver. Runs a scene file, or the embedded default scene
// (scenes/default.toml) without one. Usage: regolith --help.
#include "apps/regolith/DefaultScene.hpp"
#include "apps/regolith/SceneRun.hpp"
#include "core/app/RunApp.hpp"

int main(int argc, char** argv) {
    using namespace regolith;
    return core::runApp(argc, argv, "regolith", apps::defaultScene(), apps::runScene);
}
