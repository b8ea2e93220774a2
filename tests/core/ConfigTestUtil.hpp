#pragma once
/// Helpers shared by the configuration tests.
#include "core/Error.hpp"

#include <string>

namespace regolith::testing {

/// The message of the core::InputError thrown by `f`, or a marker if it threw nothing.
template <class F>
std::string inputErrorOf(F&& f) {
    try {
        f();
    } catch (core::InputError const& e) {
        return e.what();
    }
    return "(no InputError thrown)";
}

} // namespace regolith::testing
