// PETSc is loaded only when a run first needs it (gravity/petsc/PetscModule.hpp): a process
// that never touches grid gravity maps none of PETSc's libraries. This executable uses the
// plain test main, which does not start PETSc.
#include "gravity/petsc/PetscSession.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace {

/// Is a library whose file name contains `name` mapped into this process?
bool mapped(std::string const& name) {
    std::ifstream maps("/proc/self/maps");
    std::string line;
    while (std::getline(maps, line))
        if (line.find(name) != std::string::npos)
            return true;
    return false;
}

TEST(PetscModule, LoadedOnFirstUseOnly) {
    EXPECT_FALSE(mapped("libpetsc")) << "PETSc was mapped before anything asked for it";
    EXPECT_FALSE(mapped("libregolith_petsc"));
    EXPECT_FALSE(regolith::gravity::PetscSession::isInitialised()); // loads, does not start
    EXPECT_TRUE(mapped("libregolith_petsc"));
    EXPECT_TRUE(mapped("libpetsc"));
    EXPECT_NE(std::string(regolith::gravity::PetscSession::version()).find("Petsc"),
              std::string::npos);
}

} // namespace
