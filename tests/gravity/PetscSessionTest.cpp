// The PETSc flavour of the test main: PETSc is initialised on every rank before the tests run
// (a second PetscSession in the same process must not re-initialise or finalise it).
#include "gravity/petsc/PetscSession.hpp"

#include "core/mpi/Comm.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace regolith;

TEST(PetscSession, InitialisedByTheTestMain) {
    EXPECT_TRUE(gravity::PetscSession::isInitialised());
    std::string const version = gravity::PetscSession::version();
    EXPECT_NE(version.find("Petsc"), std::string::npos) << version;
}

TEST(PetscSession, NestedSessionLeavesPetscRunning) {
    int argc = 0;
    char** argv = nullptr;
    { gravity::PetscSession nested(argc, argv); }
    EXPECT_TRUE(gravity::PetscSession::isInitialised());
    core::Comm world;
    EXPECT_EQ(world.allReduce(1, core::ReduceOp::Sum), world.size());
}
