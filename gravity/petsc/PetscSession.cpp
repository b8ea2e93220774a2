#include "gravity/petsc/PetscSession.hpp"

#include "core/Error.hpp"

#include <petscsys.h>

#include <string>

namespace regolith::gravity {

PetscSession::PetscSession(int& argc, char**& argv) {
    if (isInitialised())
        return;
    PetscErrorCode const ierr = PetscInitialize(&argc, &argv, nullptr, nullptr);
    if (ierr != 0)
        throw core::Error("PetscInitialize failed with error code " + std::to_string(ierr));
    m_owner = true;
}

PetscSession::~PetscSession() {
    if (m_owner)
        PetscFinalize();
}

bool PetscSession::isInitialised() {
    PetscBool initialised = PETSC_FALSE;
    PetscInitialized(&initialised);
    return initialised == PETSC_TRUE;
}

char const* PetscSession::version() {
    static char text[256] = {};
    if (text[0] == '\0')
        PetscGetVersion(text, sizeof text);
    return text;
}

} // namespace regolith::gravity
