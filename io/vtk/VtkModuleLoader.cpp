// Loads libregolith_vtk.so (VtkModule.hpp) on the first call of module().
#include "core/module/SharedModule.hpp"
#include "io/vtk/VtkModule.hpp"

namespace regolith::io::vtkxml {

Module& module() {
    // Loaded once (thread-safe); a failed load throws and is tried again on the next call.
    static Module& loaded = core::loadSharedModule<Module>(
        {"libregolith_vtk.so", "REGOLITH_VTK_MODULE", REGOLITH_SHARED_MODULE_PATH,
         REGOLITH_INSTALLED_MODULE_DIR, "regolith_vtk_module", "VTK output needs VTK"});
    return loaded;
}

} // namespace regolith::io::vtkxml
