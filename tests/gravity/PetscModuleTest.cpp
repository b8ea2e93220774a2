// PETSc is loaded only when a run first needs it (gravity/petsc/PetscModule.hpp): a process
// that never touches grid gravity maps none of PETSc's libraries. This executable uses the
// plain test main, which does not start PETSc.
#include "gravity/petsc/PetscSession.hpp"
#include "tests/harness/MappedLibraries.hpp"

#include <gtest/gtest.h>

#include <string>

namespace {

using regolith::test::isMapped;

TEST(PetscModule, LoadedOnFirstUseOnly) {
    EXPECT_FALSE(isMapped("libpetsc")) << "PETSc was mapped before anything asked for it";
    EXPECT_FALSE(isMapped("libregolith_petsc"));
    EXPECT_FALSE(regolith::gravity::PetscSession::isInitialised()); // loads, does not start
    EXPECT_TRUE(isMapped("libregolith_petsc"));
    EXPECT_TRUE(isMapped("libpetsc"));
    EXPECT_NE(std::string(regolith::gravity::PetscSession::version()).find("Petsc"),
              std::string::npos);
}

} // namespace
