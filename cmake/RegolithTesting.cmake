# regolith_add_mpi_test(<target> RANKS 1 2 4 [LABELS unit mpi] [ARGS ...] [TIMEOUT s])
# Registers <target> once per rank count as <target>.np<N>, run through mpiexec with
# --oversubscribe and the variables Open MPI needs when run as root.
# The tests run on one node: Open MPI's ob1 messaging over shared memory, without probing for
# UCX's network transports first (0.2 s less per mpiexec; ~300 tests start one or more).
set(REGOLITH_MPI_TEST_ENV
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
    OMPI_MCA_pml=ob1 ASAN_OPTIONS=detect_leaks=0)

# regolith_isolate_mpi_sessions(): gives each test registered in the calling directory its own
# Open MPI session directory under the build tree. Open MPI 4 removes the shared
# /tmp/ompi.<host>.<uid> when its last job ends; a job that ctest -j starts in that moment fails
# with "A call to mkdir was unable to create the desired directory" (open-mpi/ompi#8510).
# Call it at the end of every CMakeLists.txt that adds tests.
function(regolith_isolate_mpi_sessions)
  get_directory_property(tests TESTS)
  foreach(test IN LISTS tests)
    set_property(TEST ${test} APPEND PROPERTY ENVIRONMENT
                 "OMPI_MCA_orte_tmpdir_base=${CMAKE_BINARY_DIR}/mpi-sessions/${test}")
  endforeach()
endfunction()

function(regolith_add_mpi_test target)
  cmake_parse_arguments(ARG "" "TIMEOUT;NAME" "RANKS;LABELS;ARGS" ${ARGN})
  if(NOT ARG_RANKS)
    set(ARG_RANKS 1)
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  if(NOT ARG_NAME)
    set(ARG_NAME ${target})
  endif()
  foreach(np IN LISTS ARG_RANKS)
    set(test_name ${ARG_NAME}.np${np})
    add_test(NAME ${test_name}
             COMMAND ${REGOLITH_MPIEXEC} -n ${np} --oversubscribe
                     $<TARGET_FILE:${target}> ${ARG_ARGS})
    set(labels ${ARG_LABELS})
    if(np GREATER 1)
      list(APPEND labels mpi)
    endif()
    list(REMOVE_DUPLICATES labels)
    set_tests_properties(${test_name} PROPERTIES
      ENVIRONMENT "${REGOLITH_MPI_TEST_ENV}" LABELS "${labels}" TIMEOUT ${ARG_TIMEOUT}
      PROCESSORS ${np})
  endforeach()
endfunction()

# regolith_add_test_executable(<name> SOURCES ... LIBS ... [WITH_PETSC]): a GoogleTest
# executable linked with the MPI-aware main (tests/harness); WITH_PETSC also initialises PETSc.
function(regolith_add_test_executable name)
  cmake_parse_arguments(ARG "WITH_PETSC" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  regolith_target_defaults(${name})
  if(ARG_WITH_PETSC)
    target_link_libraries(${name} PRIVATE ${ARG_LIBS} regolith_test_main_petsc)
  else()
    target_link_libraries(${name} PRIVATE ${ARG_LIBS} regolith_test_main)
  endif()
endfunction()
