#include "gravity/petsc/PetscSession.hpp"

#include "core/Error.hpp"
#include "gravity/petsc/PetscModule.hpp"

#include <string>

namespace regolith::gravity {

PetscSession::PetscSession(int& argc, char**& argv) {
    try {
        m_owner = petsc::module().initialize(argc, argv);
    } catch (petsc::Failure const& e) {
        throw core::Error(e.what());
    }
}

PetscSession::~PetscSession() {
    if (m_owner)
        petsc::module().finalize();
}

bool PetscSession::isInitialised() {
    return petsc::module().initialized();
}

char const* PetscSession::version() {
    static std::string const text = petsc::module().version();
    return text.c_str();
}

} // namespace regolith::gravity
