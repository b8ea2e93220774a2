// Loads libregolith_petsc.so (PetscModule.hpp) on the first call of module().
#include "core/Error.hpp"
#include "gravity/petsc/PetscModule.hpp"

#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace regolith::gravity::petsc {

namespace {

/// Where the module may be: $REGOLITH_PETSC_MODULE, the build tree's copy (compiled in), and
/// ../lib/ beside the executable (an installed layout).
std::vector<std::string> candidates() {
    std::vector<std::string> out;
    if (char const* env = std::getenv("REGOLITH_PETSC_MODULE"); env && env[0] != '\0')
        out.emplace_back(env);
    out.emplace_back(REGOLITH_PETSC_MODULE_PATH);
    std::error_code error;
    std::filesystem::path const exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        std::string const installed =
            (exe.parent_path().parent_path() / "lib" / "libregolith_petsc.so").string();
        if (installed != out.back()) // the build tree has that layout too
            out.push_back(installed);
    }
    return out;
}

Module* load() {
    std::string tried;
    for (std::string const& path : candidates()) {
        if (!std::filesystem::exists(path)) {
            tried += "\n  " + path + ": no such file";
            continue;
        }
        // RTLD_GLOBAL: PETSc's own plug-ins resolve against the libraries it brought.
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
        if (handle == nullptr) {
            char const* e = dlerror();
            tried += "\n  " + path + ": " + (e ? e : "dlopen failed");
            continue;
        }
        auto* entry = reinterpret_cast<Module* (*)()>(dlsym(handle, "regolith_petsc_module"));
        if (entry == nullptr)
            throw core::Error(path + " has no symbol regolith_petsc_module");
        return entry(); // never unloaded: PETSc stays until the process ends
    }
    throw core::Error("grid gravity needs PETSc, from the module libregolith_petsc.so; tried:" +
                      tried + "\n(set REGOLITH_PETSC_MODULE to its path)");
}

} // namespace

Module& module() {
    // Loaded once (thread-safe); a failed load throws and is tried again on the next call.
    static Module* const loaded = load();
    return *loaded;
}

} // namespace regolith::gravity::petsc
