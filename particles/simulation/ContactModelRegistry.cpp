#include "particles/simulation/ContactModelRegistry.hpp"

#include "core/Error.hpp"

#include <algorithm>
#include <utility>

namespace regolith::particles {

void addBuiltInContactModels(ContactModelRegistry& registry); // ContactModels.cpp

void ContactModelRegistry::add(ContactModelEntry entry) {
    if (find(entry.name) != nullptr)
        throw core::Error("contact model registry: \"" + entry.name + "\" is registered twice");
    if (entry.name.empty() || !entry.make)
        throw core::Error("contact model registry: an entry needs a name and a factory");
    m_entries.push_back(std::move(entry));
}

ContactModelEntry const* ContactModelRegistry::find(std::string_view name) const {
    auto const it = std::find_if(m_entries.begin(), m_entries.end(),
                                 [&](ContactModelEntry const& e) { return e.name == name; });
    return it == m_entries.end() ? nullptr : &*it;
}

std::vector<std::string_view> ContactModelRegistry::names() const {
    std::vector<std::string_view> out;
    for (ContactModelEntry const& e : m_entries)
        out.emplace_back(e.name);
    return out;
}

ContactModelRegistry& contactModels() {
    static ContactModelRegistry registry = [] {
        ContactModelRegistry r;
        addBuiltInContactModels(r);
        return r;
    }();
    return registry;
}

ContactModelEntry const& contactModelEntry(core::ConfigTable const& contact) {
    ContactModelRegistry const& registry = contactModels();
    auto const names = registry.names();
    std::size_t const k = contact.getChoiceOr("model", names, 0);
    return *registry.find(names[k]);
}

} // namespace regolith::particles
