#include "gravity/petsc/PetscSession.hpp"
#include "tests/harness/TestEnvironment.hpp"

#include <memory>

namespace regolith::testing {

namespace {
std::unique_ptr<gravity::PetscSession> session;
}

ExtraEnvironment::ExtraEnvironment(int& argc, char**& argv) {
    session = std::make_unique<gravity::PetscSession>(argc, argv);
}
ExtraEnvironment::~ExtraEnvironment() {
    session.reset();
}

} // namespace regolith::testing
