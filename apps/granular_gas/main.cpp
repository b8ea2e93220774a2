// granular_gas: the sparse granular gas (Eibl & Rüde 2018, Table 1). Runs scenes/granular-gas.toml
// (compiled in) or a scene file given on the command line; the [granular_gas] section of the scene
// lays it out over the ranks (apps/scenarios/Scenarios.hpp). Prints PUpCS and writes the run
// summary (--json). Usage: granular_gas --help.
#include "apps/common/ReferenceScenes.hpp"
#include "apps/regolith/SceneRun.hpp"
#include "core/app/RunApp.hpp"

int main(int argc, char** argv) {
    using namespace regolith;
    return core::runApp(argc, argv, "granular_gas", apps::granularGasScene(), apps::runScene);
}
