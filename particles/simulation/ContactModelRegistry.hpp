#pragma once
/// The contact models a scene may name (contact.model): each registered under its name with
/// the material keys it reads (its elasticity), a check of its own [contact] keys and a
/// factory. A new model is one file -- its kernel, its keys and their checks, its contact time
/// (TimeStepGuard), its interaction range (AnyContactModel.hpp) and its entry -- plus one line
/// registering the entry: in the built-in list (ContactModels.cpp), or from a program of one's
/// own before it reads a scene (docs/guide/library.md, "Adding a contact model").
#include "core/config/ConfigTable.hpp"
#include "particles/kernels/MaterialMixing.hpp"
#include "particles/kernels/TangentialSpring.hpp"
#include "particles/simulation/AnyContactModel.hpp"

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace regolith::particles {

/// What a model's factory builds from: the scene's [contact] table (the model's own keys),
/// every material type's properties (type t is types[t]) and model C's rolling settings.
struct ContactModelInputs {
    core::ConfigTable const& contact;
    std::span<MaterialProperties const> types;
    RollingSpring const& rolling;
};

/// One registered model.
struct ContactModelEntry {
    std::string name;      ///< contact.model's value
    Elasticity elasticity; ///< which material keys it reads (MaterialMixing.hpp)
    /// Reads and checks the model's own keys of [contact] (each named in the message of the
    /// core::InputError it throws), so that a scene is refused before the run starts and its
    /// keys are no typos; may be empty (no keys of its own).
    std::function<void(core::ConfigTable const&)> checkKeys;
    std::function<AnyContactModel(ContactModelInputs const&)> make;
};

class ContactModelRegistry {
public:
    /// Registers `entry`; throws core::Error if the name is taken or a function is missing.
    void add(ContactModelEntry entry);
    /// The entry named `name`, nullptr if none.
    [[nodiscard]] ContactModelEntry const* find(std::string_view name) const;
    /// The registered names, in registration order (the built-in models first).
    [[nodiscard]] std::vector<std::string_view> names() const;

private:
    std::vector<ContactModelEntry> m_entries;
};

/// The process's registry, holding the built-in models (ContactModels.cpp) from the first
/// call on. Not thread-safe: register before the run starts.
ContactModelRegistry& contactModels();

/// The entry of the model `contact` (a scene's [contact] table) names with its key "model"
/// (default "spring-dashpot"). Throws core::InputError naming contact.model, listing the
/// registered names, if no model of that name is registered.
[[nodiscard]] ContactModelEntry const& contactModelEntry(core::ConfigTable const& contact);

} // namespace regolith::particles
