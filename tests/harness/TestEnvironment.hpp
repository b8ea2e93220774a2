#pragma once
/// Hook for libraries that need initialising after MPI in a test executable. The default
/// (NoExtraEnvironment.cpp) does nothing; the PETSc variant (PetscEnvironment.cpp)
/// initialises PETSc on MPI_COMM_WORLD and finalises it before MPI.
namespace regolith::testing {

class ExtraEnvironment {
public:
    ExtraEnvironment(int& argc, char**& argv);
    ~ExtraEnvironment();
    ExtraEnvironment(ExtraEnvironment const&) = delete;
    ExtraEnvironment& operator=(ExtraEnvironment const&) = delete;
};

} // namespace regolith::testing
