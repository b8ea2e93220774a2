#pragma once
/// The self-gravity methods as a registry: each method is an entry (its name for
/// `gravity.self`, what it needs from the run, its own [gravity] keys and a factory) whose
/// objects compute the field at the grains behind one `evaluate`. SelfGravityForces builds the
/// method named by SelfGravityConfig::method and leaves the rest (update policy, extrapolation,
/// checks, records) the same for all. The built-in methods are listed in
/// methods/BuiltinGravityMethods.cpp; a program adds its own with registerGravityMethod()
/// before it builds the run (docs/guide/library.md, "Adding a self-gravity method").
#include "core/config/ConfigTable.hpp"
#include "core/mpi/Comm.hpp"
#include "coupling/gravity/SelfGravityForces.hpp"
#include "domain/BlockForest.hpp"
#include "gravity/common/PointMasses.hpp"
#include "gravity/field/GridFieldsView.hpp"

#include <any>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace regolith::coupling {

/// What a method is built from: the communicator of the run and the forest of this block
/// assignment (both outlive the method; a rebalance builds a new method), and the settings.
struct GravityMethodInput {
    core::Comm const& comm;
    domain::BlockForest const& forest;
    SelfGravityConfig const& config;
};

/// One self-gravity method on one block assignment.
class GravityMethod {
public:
    virtual ~GravityMethod() = default;
    /// The field at this rank's grains: overwrites `out` (n accelerations, positions wrapped on
    /// periodic axes as the synchronisation leaves masters) and returns ½ Σ m φ over all
    /// ranks [energy]. In reproducible mode the grains come in uid order, and the result must
    /// depend on them only (not on the block layout or the rank count). COLLECTIVE.
    virtual double evaluate(gravity::PointMasses const& grains, gravity::FieldOut out) = 0;
    /// The cell fields (density, potential, acceleration) of the last evaluate(), for a method
    /// on the blocks' grid; nullopt for the others. Not collective.
    [[nodiscard]] virtual std::optional<gravity::GridFieldsView> gridFields() const {
        return std::nullopt;
    }
    /// The next evaluate() starts its iterative solve from zero, not from the last solution
    /// (a restart's bits; nothing for a method without one). Not collective.
    virtual void resetInitialGuess() {}
};

/// A method as the registry knows it.
struct GravityMethodEntry {
    std::string name; ///< its `gravity.self` value ("none" and "auto" are taken)
    /// It works on the blocks' cells (domain.cells_per_block, given in the config): their
    /// count weighs in the load balance and the run writes its grid fields.
    bool usesGrid = false;
    /// It has periodic images; a method without them (free space) is refused in a periodic
    /// domain, where grains across a face would attract through the whole domain.
    bool periodic = false;
    bool softens = false;   ///< gravity.softening (a Plummer length) applies to it
    bool usesTheta = false; ///< gravity.theta sets its accuracy (the error warning names it)
    /// Reads and checks the method's own [gravity] keys (an error names the key, as the
    /// getters of core::ConfigTable do) into the value `make` finds in config.options. Called
    /// for the scene's method only, so that its keys are known keys. Empty: no keys of its own.
    std::function<std::any(core::ConfigTable const& gravity)> readKeys;
    /// The method for a block assignment; throws core::InputError naming the key of a bad
    /// setting, on every rank alike. COLLECTIVE over input.comm.
    std::function<std::unique_ptr<GravityMethod>(GravityMethodInput const& input)> make;
};

/// GravityMethodEntry::make for a method built from the input alone:
/// `e.make = makeGravityMethod<MySum>`.
template <class Method>
[[nodiscard]] std::unique_ptr<GravityMethod> makeGravityMethod(GravityMethodInput const& input) {
    return std::make_unique<Method>(input);
}

/// Adds a method to the registry, after the built-in ones. Throws core::Error for a name that
/// is empty, "none", "auto" or registered already, or an entry without `make`. Call it alike
/// on every rank, before the runs that use the method. Not collective.
void registerGravityMethod(GravityMethodEntry entry);
/// The entry of `name`, or nullptr. Not collective.
[[nodiscard]] GravityMethodEntry const* findGravityMethod(std::string_view name);
/// The entry of `name`; throws core::InputError naming gravity.self and listing the registered
/// methods when there is none. Not collective.
[[nodiscard]] GravityMethodEntry const& gravityMethod(std::string_view name);
/// The registered names, the built-in ones first, in registration order. Not collective.
[[nodiscard]] std::vector<std::string> gravityMethodNames();

} // namespace regolith::coupling
