#include "core/Error.hpp"
#include "coupling/gravity/GravityMethod.hpp"
#include "coupling/gravity/methods/BuiltinGravityMethods.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace regolith::coupling {

namespace {

/// The registered methods, the built-in ones first (made on the first use).
std::vector<GravityMethodEntry>& registry() {
    static std::vector<GravityMethodEntry> entries = builtinGravityMethods();
    return entries;
}

std::string quotedList(std::vector<std::string> const& names) {
    std::string out;
    for (std::string const& n : names)
        out += fmt::format("{}\"{}\"", out.empty() ? "" : ", ", n);
    return out;
}

} // namespace

void registerGravityMethod(GravityMethodEntry entry) {
    if (entry.name.empty() || entry.name == "none" || entry.name == "auto")
        throw core::Error(fmt::format("registerGravityMethod: the name \"{}\" is not free: "
                                      "\"none\" and \"auto\" are gravity.self's own words",
                                      entry.name));
    if (findGravityMethod(entry.name))
        throw core::Error(
            fmt::format("registerGravityMethod: a self-gravity method \"{}\" is registered already",
                        entry.name));
    if (!entry.make)
        throw core::Error(fmt::format(
            "registerGravityMethod: the method \"{}\" has no factory (make)", entry.name));
    registry().push_back(std::move(entry));
}

GravityMethodEntry const* findGravityMethod(std::string_view name) {
    auto const& entries = registry();
    auto const it = std::find_if(entries.begin(), entries.end(),
                                 [&](GravityMethodEntry const& e) { return e.name == name; });
    return it == entries.end() ? nullptr : &*it;
}

GravityMethodEntry const& gravityMethod(std::string_view name) {
    if (GravityMethodEntry const* entry = findGravityMethod(name))
        return *entry;
    throw core::InputError(
        fmt::format("gravity.self = \"{}\": no such self-gravity method; registered: {}", name,
                    quotedList(gravityMethodNames())));
}

std::vector<std::string> gravityMethodNames() {
    std::vector<std::string> names;
    for (GravityMethodEntry const& e : registry())
        names.push_back(e.name);
    return names;
}

} // namespace regolith::coupling
