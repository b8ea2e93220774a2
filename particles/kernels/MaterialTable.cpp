#include "particles/kernels/MaterialTable.hpp"

#include "core/Error.hpp"

#include <string>

namespace regolith::particles {

void throwBadMaterialType(std::uint32_t type, std::size_t numTypes) {
    throw core::InputError("material type " + std::to_string(type) + " is not below the " +
                           std::to_string(numTypes) + " declared types");
}

} // namespace regolith::particles
