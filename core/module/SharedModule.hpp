#pragma once
/// Regolith's own shared modules: a third-party library (PETSc, VTK, HDF5) wrapped behind a
/// plain C++ interface in a library of its own, opened with dlopen the first time a run needs
/// it. A run that never needs one maps none of its libraries, which are megabytes of resident
/// pages in every process (docs/notes/memory.md). A module exports one `extern "C"`
/// function returning its interface; it links no static Regolith library, so everything
/// that crosses the boundary is header-only (standard types, MPI handles, plain structs).
#include <string>

namespace regolith::core {

struct SharedModuleSpec {
    std::string file;        ///< e.g. "libregolith_petsc.so"
    std::string envVariable; ///< a path that overrides the others, e.g. "REGOLITH_PETSC_MODULE"
    std::string buildPath;   ///< the build tree's copy (compiled in)
    std::string installDir;  ///< where `cmake --install` puts it (compiled in)
    std::string entry;       ///< the exported function, e.g. "regolith_petsc_module"
    std::string neededFor;   ///< the error's subject, e.g. "grid gravity needs PETSc"
};

/// Opens the module (never closed: its libraries stay until the process ends) from
/// $envVariable, else ../lib/ beside the executable (the build tree's and an installed
/// regolith's layout), else installDir (a program of one's own built against the installed
/// package), else buildPath, and returns the address of its entry function. Throws core::Error
/// naming every path tried and the loader's message. Not collective; thread-safe as dlopen is.
[[nodiscard]] void* openSharedModule(SharedModuleSpec const& spec);

/// openSharedModule, then calls the entry function `Interface* entry()`.
template <class Interface>
[[nodiscard]] Interface& loadSharedModule(SharedModuleSpec const& spec) {
    return *reinterpret_cast<Interface* (*)()>(openSharedModule(spec))();
}

} // namespace regolith::core
