// bidisperse: large spheres among small grains (Eibl & Rüde 2018, Table 1 and Figs. 6-8). Runs
// scenes/bidisperse.toml (compiled in) or a scene file given on the command line; the [bidisperse]
// section of the scene lays it out over the ranks (apps/scenarios/Scenarios.hpp). Prints PUpCS and
// writes the run summary (--json). Usage: bidisperse --help.
#include "apps/common/ReferenceScenes.hpp"
#include "apps/regolith/SceneRun.hpp"
#include "core/app/RunApp.hpp"

int main(int argc, char** argv) {
    using namespace regolith;
    return core::runApp(argc, argv, "bidisperse", apps::bidisperseScene(), apps::runScene);
}
