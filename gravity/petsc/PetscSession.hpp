#pragma once
/// RAII PETSc initialisation on MPI_COMM_WORLD (MPI must already be initialised; PETSc then
/// leaves MPI_Finalize to the caller). Only the outermost session initialises and finalises
/// PETSc, so a library may open one where an app already has. The first session (or
/// isInitialised / version) loads PETSc: it lives in the shared module libregolith_petsc.so
/// (PetscModule.hpp), which no executable links. Throws core::Error if the module cannot be
/// loaded, naming the files tried.
namespace regolith::gravity {

class PetscSession {
public:
    /// Collective over MPI_COMM_WORLD. Passes argc/argv so `-ksp_*` options reach PETSc.
    PetscSession(int& argc, char**& argv);
    ~PetscSession();
    PetscSession(PetscSession const&) = delete;
    PetscSession& operator=(PetscSession const&) = delete;

    /// Is PETSc initialised (by any session) and not yet finalised?
    [[nodiscard]] static bool isInitialised();
    /// PETSc's version string, e.g. "Petsc Release Version 3.18.5".
    [[nodiscard]] static char const* version();

private:
    bool m_owner = false; ///< this session initialised PETSc and finalises it
};

} // namespace regolith::gravity
