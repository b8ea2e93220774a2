// Loads libregolith_petsc.so (PetscModule.hpp) on the first call of module().
#include "core/module/SharedModule.hpp"
#include "gravity/petsc/PetscModule.hpp"

namespace regolith::gravity::petsc {

Module& module() {
    // Loaded once (thread-safe); a failed load throws and is tried again on the next call.
    static Module& loaded = core::loadSharedModule<Module>(
        {"libregolith_petsc.so", "REGOLITH_PETSC_MODULE", REGOLITH_SHARED_MODULE_PATH,
         REGOLITH_INSTALLED_MODULE_DIR, "regolith_petsc_module", "grid gravity needs PETSc"});
    return loaded;
}

} // namespace regolith::gravity::petsc
