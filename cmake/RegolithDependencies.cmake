# Finds every external dependency. A missing one stops configuration with the Debian
# package that provides it (scripts/install-deps.sh installs them all).

function(regolith_missing what package)
  message(FATAL_ERROR
    "Regolith: ${what} not found. On Debian: apt-get install ${package} "
    "(or run scripts/install-deps.sh).")
endfunction()

find_package(MPI COMPONENTS CXX QUIET)
if(NOT MPI_CXX_FOUND)
  regolith_missing("MPI (C++ bindings)" "libopenmpi-dev openmpi-bin")
endif()

find_package(Eigen3 3.3 CONFIG QUIET)
if(NOT Eigen3_FOUND)
  regolith_missing("Eigen3" "libeigen3-dev")
endif()

find_package(PkgConfig QUIET)
if(NOT PkgConfig_FOUND)
  regolith_missing("pkg-config" "pkg-config")
endif()

# PETSc: Debian's petsc-dev installs PETSc.pc (an alternative pointing at the real build).
pkg_check_modules(PETSC QUIET IMPORTED_TARGET GLOBAL PETSc)
if(NOT PETSC_FOUND)
  regolith_missing("PETSc (pkg-config PETSc)" "petsc-dev")
endif()

# FFTW (double precision): the FFT free-space reference solver of grid gravity.
pkg_check_modules(FFTW3 QUIET IMPORTED_TARGET GLOBAL fftw3)
if(NOT FFTW3_FOUND)
  regolith_missing("FFTW 3 (pkg-config fftw3)" "libfftw3-dev")
endif()

# HDF5 built against Open MPI (parallel I/O for checkpoints).
pkg_check_modules(HDF5_MPI QUIET IMPORTED_TARGET GLOBAL hdf5-openmpi)
if(NOT HDF5_MPI_FOUND)
  regolith_missing("parallel HDF5 (pkg-config hdf5-openmpi)" "libhdf5-openmpi-dev")
endif()

find_package(VTK 9 QUIET COMPONENTS CommonCore CommonDataModel IOXML IOParallelXML
             OPTIONAL_COMPONENTS RenderingCore RenderingOpenGL2 FiltersSources IOImage)
if(NOT VTK_FOUND)
  regolith_missing("VTK 9 (CommonCore, CommonDataModel, IOXML, IOParallelXML)" "libvtk9-dev")
endif()
# Off-screen pictures (io/render, regolith-render): optional, skipped without these modules.
set(REGOLITH_HAVE_VTK_RENDERING OFF)
if(TARGET VTK::RenderingOpenGL2 AND TARGET VTK::FiltersSources AND TARGET VTK::IOImage)
  set(REGOLITH_HAVE_VTK_RENDERING ON)
endif()

find_package(tomlplusplus CONFIG QUIET)
if(NOT tomlplusplus_FOUND)
  pkg_check_modules(TOMLPP QUIET IMPORTED_TARGET GLOBAL tomlplusplus)
  if(NOT TOMLPP_FOUND)
    regolith_missing("toml++" "libtomlplusplus-dev")
  endif()
  add_library(tomlplusplus::tomlplusplus ALIAS PkgConfig::TOMLPP)
endif()

find_package(CLI11 CONFIG QUIET)
if(NOT CLI11_FOUND)
  regolith_missing("CLI11" "libcli11-dev")
endif()

find_package(fmt CONFIG QUIET)
if(NOT fmt_FOUND)
  regolith_missing("fmt" "libfmt-dev")
endif()
find_package(spdlog CONFIG QUIET)
if(NOT spdlog_FOUND)
  regolith_missing("spdlog" "libspdlog-dev")
endif()

if(REGOLITH_BUILD_TESTS)
  find_package(GTest CONFIG QUIET)
  if(NOT GTest_FOUND)
    regolith_missing("GoogleTest" "libgtest-dev libgmock-dev")
  endif()
endif()
if(REGOLITH_BUILD_BENCH)
  find_package(benchmark CONFIG QUIET)
  if(NOT benchmark_FOUND)
    regolith_missing("Google Benchmark" "libbenchmark-dev")
  endif()
endif()

find_program(REGOLITH_MPIEXEC NAMES mpiexec mpirun HINTS ${MPIEXEC_EXECUTABLE})
