#pragma once
/// Internal to gravity/ (includes PETSc): checking PETSc return codes. Every PETSc call in
/// the module goes through petscCheck(), which turns a non-zero code into a core::Error
/// naming the call and PETSc's own message. While a PetscQuiet guard lives, PETSc returns
/// error codes without printing its traceback (we report the error ourselves).
#include <petscsys.h>

#include <string>

namespace regolith::gravity::detail {

/// Throws core::Error("PETSc <what> failed: <PETSc message>") if ierr != 0.
void petscCheck(PetscErrorCode ierr, char const* what);

/// PETSc's message for the last error (empty if none).
[[nodiscard]] std::string petscMessage(PetscErrorCode ierr);

/// RAII: pushes PetscReturnErrorHandler, pops it on destruction.
class PetscQuiet {
public:
    PetscQuiet();
    ~PetscQuiet();
    PetscQuiet(PetscQuiet const&) = delete;
    PetscQuiet& operator=(PetscQuiet const&) = delete;
};

} // namespace regolith::gravity::detail
