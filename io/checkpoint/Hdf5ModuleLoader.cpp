// Loads libregolith_hdf5.so (Hdf5Module.hpp) on the first call of hdf5().
#include "core/module/SharedModule.hpp"
#include "io/checkpoint/Hdf5Module.hpp"

namespace regolith::io::detail {

Hdf5Module& hdf5() {
    // Loaded once (thread-safe); a failed load throws and is tried again on the next call.
    static Hdf5Module& loaded = core::loadSharedModule<Hdf5Module>(
        {"libregolith_hdf5.so", "REGOLITH_HDF5_MODULE", REGOLITH_SHARED_MODULE_PATH,
         REGOLITH_INSTALLED_MODULE_DIR, "regolith_hdf5_module", "checkpoints need HDF5"});
    return loaded;
}

} // namespace regolith::io::detail
