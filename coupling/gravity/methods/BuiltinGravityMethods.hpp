#pragma once
/// The self-gravity methods that come with the library, one file each in this folder.
#include "coupling/gravity/GravityMethod.hpp"

#include <vector>

namespace regolith::coupling {

/// Their entries, in the order gravity.self lists them. Not collective.
[[nodiscard]] std::vector<GravityMethodEntry> builtinGravityMethods();

} // namespace regolith::coupling
