#include "particles/storage/GrainFields.hpp"

#include "core/Error.hpp"
#include "particles/storage/GrainQuantities.hpp"

#include <algorithm>
#include <vector>

namespace regolith::particles {

namespace {

struct Declared {
    std::vector<GrainField> fields;
    std::vector<GrainFieldId> ids;
    std::uint32_t components = 0;
};

Declared& declared() {
    static Declared d;
    return d;
}

bool validName(std::string const& name) {
    return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_';
    });
}

} // namespace

GrainFieldId declareGrainField(GrainField const& field) {
    Declared& d = declared();
    if (!validName(field.name))
        throw core::Error("declareGrainField: name \"" + field.name +
                          "\": expected letters, digits and '_'");
    if (isBuiltInColumn(field.name))
        throw core::Error("declareGrainField: \"" + field.name + "\" is a built-in column");
    if (field.components != 1 && field.components != 3)
        throw core::Error("declareGrainField: \"" + field.name + "\" has " +
                          std::to_string(field.components) + " components: expected 1 or 3");
    for (std::size_t k = 0; k < d.fields.size(); ++k)
        if (d.fields[k].name == field.name) {
            if (d.fields[k].components != field.components || d.fields[k].unit != field.unit)
                throw core::Error("declareGrainField: \"" + field.name +
                                  "\" was declared before with another shape or unit");
            return d.ids[k];
        }
    GrainFieldId const id{d.components, static_cast<std::uint32_t>(field.components)};
    d.fields.push_back(field);
    d.ids.push_back(id);
    d.components += id.components;
    return id;
}

std::span<GrainField const> grainFields() {
    return declared().fields;
}

std::size_t grainFieldComponents() {
    return declared().components;
}

GrainFieldId grainFieldId(std::size_t place) {
    return declared().ids.at(place);
}

} // namespace regolith::particles
