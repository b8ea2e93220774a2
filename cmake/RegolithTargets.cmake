# regolith_add_module(<name> SOURCES ... [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# One library per module with the alias regolith::<name>; the repository root is the
# include root, so headers are included as "core/mpi/Comm.hpp".
set(REGOLITH_WARNINGS -Wall -Wextra -Wpedantic -Werror -Wshadow -Wnon-virtual-dtor
    -Wold-style-cast -Woverloaded-virtual -Wnull-dereference -Wimplicit-fallthrough)

function(regolith_target_defaults target)
  target_compile_options(${target} PRIVATE ${REGOLITH_WARNINGS})
  target_compile_features(${target} PUBLIC cxx_std_20)
endfunction()

function(regolith_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  add_library(regolith_${name} ${ARG_SOURCES})
  add_library(regolith::${name} ALIAS regolith_${name})
  target_include_directories(regolith_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(regolith_${name} PUBLIC ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  regolith_target_defaults(regolith_${name})
endfunction()

function(regolith_add_app name)
  add_executable(${name} ${ARGN})
  regolith_target_defaults(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bin)
endfunction()
