// dense_ramp: the dense hcp packing on a 30-degree ramp (Eibl & Rüde 2018, Table 1). Runs
// scenes/dense-ramp.toml (compiled in) or a scene file given on the command line; the [dense_ramp]
// section of the scene lays it out over the ranks (apps/scenarios/Scenarios.hpp). Prints PUpCS and
// writes the run summary (--json). Usage: dense_ramp --help.
#include "apps/common/ReferenceScenes.hpp"
#include "apps/regolith/SceneRun.hpp"
#include "core/app/RunApp.hpp"

int main(int argc, char** argv) {
    using namespace regolith;
    return core::runApp(argc, argv, "dense_ramp", apps::denseRampScene(), apps::runScene);
}
