#include "coupling/gravity/methods/BuiltinGravityMethods.hpp"

namespace regolith::coupling {

// Each defined in its own file of this folder.
GravityMethodEntry directSumMethod();
GravityMethodEntry barnesHutMethod();
GravityMethodEntry particleMeshMethod();
GravityMethodEntry p3mMethod();
GravityMethodEntry occupiedCellsMethod();
GravityMethodEntry treeNodesMethod();
GravityMethodEntry mutualTreeMethod();

std::vector<GravityMethodEntry> builtinGravityMethods() {
    return {directSumMethod(),     barnesHutMethod(), particleMeshMethod(), p3mMethod(),
            occupiedCellsMethod(), treeNodesMethod(), mutualTreeMethod()};
}

} // namespace regolith::coupling
