// gravity.self = "occupied-cells" and "tree-nodes": the second paper's methods, the field at
// the nodes of a lattice around the occupied cells, interpolated to the grains
// (gravity/baselines).
#include "core/Error.hpp"
#include "coupling/gravity/GravityMethod.hpp"
#include "gravity/baselines/GridMethods.hpp"

#include <fmt/format.h>

#include <string>
#include <type_traits>

namespace regolith::coupling {

namespace {

/// The node methods' options: the lattice from the domain's minimum corner; the
/// neighbourhood is the node distance unless given (the methods check the rest, naming
/// gravity.grid_spacing, gravity.theta, ...).
gravity::baselines::GridMethodOptions nodeOptions(GravityMethodInput const& in,
                                                  std::string const& name) {
    SelfGravityConfig const& c = in.config;
    if (!(c.gridSpacing > 0.0))
        throw core::InputError(fmt::format(
            "gravity.grid_spacing: required with gravity.self = \"{}\" (the node distance; "
            "the paper uses 2.5 x the largest grain diameter)",
            name));
    gravity::baselines::GridMethodOptions o;
    o.G = c.G;
    o.grid.origin = in.forest.domain().min;
    o.grid.spacing = c.gridSpacing;
    o.theta = c.theta;
    o.allowLargeTheta = c.allowLargeTheta;
    o.neighbourhood = c.neighbourhood >= 0.0 ? c.neighbourhood : c.gridSpacing;
    return o;
}

/// Either baseline (OccupiedCells, TreeAtNodes: the same interface).
template <class Baseline>
class NodeMethod final : public GravityMethod {
public:
    NodeMethod(GravityMethodInput const& in, std::string const& name)
        : m_comm(in.comm)
        , m_nodes(nodeOptions(in, name)) {}
    double evaluate(gravity::PointMasses const& grains, gravity::FieldOut out) override {
        return m_nodes.evaluate(m_comm, grains, out);
    }

private:
    core::Comm const& m_comm;
    Baseline m_nodes;
};

template <class Baseline>
GravityMethodEntry nodeMethod(std::string const& name) {
    GravityMethodEntry e;
    e.name = name;
    e.usesTheta = std::is_same_v<Baseline, gravity::baselines::TreeAtNodes>;
    e.make = [name](GravityMethodInput const& in) {
        return std::make_unique<NodeMethod<Baseline>>(in, name);
    };
    return e;
}

} // namespace

GravityMethodEntry occupiedCellsMethod() {
    return nodeMethod<gravity::baselines::OccupiedCells>("occupied-cells"); // every grain summed
}

GravityMethodEntry treeNodesMethod() {
    return nodeMethod<gravity::baselines::TreeAtNodes>("tree-nodes"); // a tree walked per node
}

} // namespace regolith::coupling
