#include "gravity/poisson/PetscCheck.hpp"

#include "core/Error.hpp"

namespace regolith::gravity::detail {

std::string petscMessage(PetscErrorCode ierr) {
    char const* text = nullptr;
    char* specific = nullptr;
    if (PetscErrorMessage(ierr, &text, &specific) != 0)
        return "(no message)";
    std::string out = text ? text : "";
    if (specific && specific[0] != '\0')
        out += std::string(": ") + specific;
    return out;
}

void petscCheck(PetscErrorCode ierr, char const* what) {
    if (ierr != 0)
        throw core::Error(std::string("PETSc ") + what + " failed: " + petscMessage(ierr));
}

PetscQuiet::PetscQuiet() {
    petscCheck(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
}

PetscQuiet::~PetscQuiet() {
    PetscPopErrorHandler();
}

} // namespace regolith::gravity::detail
