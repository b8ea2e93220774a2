# regolith_add_module(<name> SOURCES ... [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# One library per module with the alias regolith::<name>; the repository root is the
# include root, so headers are included as "core/mpi/Comm.hpp". Installed (cmake/RegolithInstall.cmake)
# as the same regolith::<name>, headers under <prefix>/include/regolith/<name>/.
set(REGOLITH_WARNINGS -Wall -Wextra -Wpedantic -Werror -Wshadow -Wnon-virtual-dtor
    -Wold-style-cast -Woverloaded-virtual -Wnull-dereference -Wimplicit-fallthrough)

# Code generation, for every target:
# -fno-math-errno   sqrt compiles to the instruction, so loops that take roots vectorise
#                   (SpringDashpotBatch); nothing here reads errno after a math call.
# -ffp-contract=off no fused multiply-add contraction: an expression gives the same bits
#                   wherever the compiler inlines it and whatever the instruction set, which the
#                   "same bits on every path" rules rely on (PairRule.hpp, reproducible mode).
# REGOLITH_NATIVE   -march=native: the instruction set of the machine that builds (and runs)
#                   the code, as waLBerla's WALBERLA_OPTIMIZE_FOR_LOCALHOST. Our own loops give
#                   the same bits with or without it (no contraction, no reassociation: the DEM
#                   checksums are unchanged); Eigen's vectorised sums over long vectors (gravity)
#                   may add in another order at another vector width. Without AVX-512
#                   (-mno-avx512f: at most AVX2), the lane kernels below excepted: GCC 12 warns
#                   falsely in its AVX-512 headers through Eigen (GCC bug 105593,
#                   maybe-uninitialized), and elsewhere wider vectors bought nothing measurable
#                   (the particles module built with AVX-512: same time).
option(REGOLITH_NATIVE "Optimise for the building machine (-march=native)" ON)
set(REGOLITH_CODEGEN -fno-math-errno -ffp-contract=off)
set(REGOLITH_ABI_FLAGS "")
if(REGOLITH_NATIVE)
  # Part of the ABI: Eigen aligns its fixed-size types (Quat, in ParticleInit and the storage
  # records) to the widest vector the instruction set has, so a program built against the
  # modules must compile with the same set (regolith_add_module makes it a usage requirement).
  set(REGOLITH_ABI_FLAGS -march=native -mno-avx512f)
  list(APPEND REGOLITH_CODEGEN ${REGOLITH_ABI_FLAGS})
endif()

# REGOLITH_LANE_CODEGEN, for the files whose loops run over structure-of-arrays lanes
# (SpringDashpotBatch, OverlapScreen, CellCandidatesLanes): 512-bit AVX-512 where the building
# machine has it. The cells' candidate sweep also checks the processor at run time and sweeps
# one by one without it (so that valgrind, which has no AVX-512, runs the other scenes' paths).
# Those loops are latency-bound, not throughput-bound: one contact's chain of roots and
# divisions is longer than the reorder window can hide, so eight lanes per instruction instead
# of four cut the batch model's time by a third even on Zen 4, which splits a 512-bit operation
# into two 256-bit halves (particles_bench springDashpotBatch/0: 11.8 -> 7.8 ns per contact;
# 256-bit AVX-512 with its 32 registers: 11.4 ns; Zen 3 without AVX-512, AVX2: 17.5 ns). Without
# it the lane files must not use 512-bit vector types: GCC splits their shuffles into element
# moves through the stack (TransposedLoads.hpp). The same IEEE operations in every lane, no
# contraction: the same bits. They include no Eigen code that GCC bug 105593 trips over.
set(REGOLITH_LANE_CODEGEN "")
if(REGOLITH_NATIVE)
  include(CheckCXXSourceRuns)
  set(CMAKE_REQUIRED_FLAGS "-mavx512f -mavx512vl -mavx512dq")
  check_cxx_source_runs([=[
    int main() {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                       __builtin_cpu_supports("avx512dq") ? 0 : 1;
    }]=] REGOLITH_HOST_HAS_AVX512)
  unset(CMAKE_REQUIRED_FLAGS)
  if(REGOLITH_HOST_HAS_AVX512)
    set(REGOLITH_LANE_CODEGEN -mavx512f -mavx512vl -mavx512dq -mprefer-vector-width=512)
  endif()
endif()

function(regolith_target_defaults target)
  target_compile_options(${target} PRIVATE ${REGOLITH_WARNINGS} ${REGOLITH_CODEGEN})
  target_compile_features(${target} PUBLIC cxx_std_20)
endfunction()

function(regolith_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  add_library(regolith_${name} ${ARG_SOURCES})
  add_library(regolith::${name} ALIAS regolith_${name})
  target_include_directories(regolith_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/regolith>)
  target_link_libraries(regolith_${name} PUBLIC ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  regolith_target_defaults(regolith_${name})
  target_compile_options(regolith_${name} INTERFACE ${REGOLITH_ABI_FLAGS})
  regolith_install_module(${name})
endfunction()

# A shared module (core/module/SharedModule.hpp): library `lib<output>.so` in <build>/lib, built
# with `loader` (a module target that opens it) and its path compiled into `loader_source` as
# REGOLITH_SHARED_MODULE_PATH. It links no static Regolith library.
function(regolith_add_shared_module target)
  cmake_parse_arguments(ARG "" "OUTPUT_NAME;LOADER;LOADER_SOURCE" "SOURCES;LIBS" ${ARGN})
  add_library(${target} MODULE ${ARG_SOURCES})
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${target} PRIVATE ${ARG_LIBS})
  regolith_target_defaults(${target})
  set_target_properties(${target} PROPERTIES OUTPUT_NAME ${ARG_OUTPUT_NAME}
    LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/lib)
  add_dependencies(${ARG_LOADER} ${target})
  set_source_files_properties(${ARG_LOADER_SOURCE} TARGET_DIRECTORY ${ARG_LOADER}
    PROPERTIES COMPILE_DEFINITIONS
    "REGOLITH_SHARED_MODULE_PATH=\"$<TARGET_FILE:${target}>\";REGOLITH_INSTALLED_MODULE_DIR=\"${CMAKE_INSTALL_FULL_LIBDIR}\"")
  install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime)
endfunction()

function(regolith_add_app name)
  add_executable(${name} ${ARGN})
  regolith_target_defaults(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bin)
endfunction()

# regolith_install_app(<name>...): the executables a user runs, into <prefix>/bin.
function(regolith_install_app)
  install(TARGETS ${ARGN} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
endfunction()
