# The rubble-pile app spin_up end to end (docs/guide/rubble-piles.md): its bad input refused
# with one message on 1 and 4 ranks, and a small fly-by run. Included by
# tests/apps/CMakeLists.txt.

# spin_up_app_test(<name> ARGS ... [FAIL MESSAGE <text>] [STDOUT_HAS <text> ...])
# Registers spin_up.<name>.np1 and .np4, run with RunAppCheck.cmake.
function(spin_up_app_test name)
  cmake_parse_arguments(ARG "FAIL" "MESSAGE" "ARGS;STDOUT_HAS" ${ARGN})
  foreach(np IN ITEMS 1 4)
    set(defs -DMPIEXEC=${REGOLITH_MPIEXEC} -DNP=${np} -DAPP=$<TARGET_FILE:spin_up>)
    if(ARG_FAIL)
      list(APPEND defs -DEXIT_CODE=2 -DEXPECT_FAIL=1 "-DMESSAGE=${ARG_MESSAGE}")
    endif()
    if(ARG_STDOUT_HAS)
      string(REPLACE ";" "|" texts "${ARG_STDOUT_HAS}")
      list(APPEND defs "-DSTDOUT_HAS=${texts}")
    endif()
    string(REPLACE ";" "|" joined "${ARG_ARGS};--output;${app_test_out}/spin_up.${name}.np${np}")
    add_test(NAME spin_up.${name}.np${np}
             COMMAND ${CMAKE_COMMAND} ${defs} "-DARGS=${joined}"
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/RunAppCheck.cmake)
    set(labels scene)
    if(np GREATER 1)
      list(APPEND labels mpi)
    endif()
    set_tests_properties(spin_up.${name}.np${np} PROPERTIES ENVIRONMENT "${REGOLITH_MPI_TEST_ENV}"
                         LABELS "${labels}" TIMEOUT 90 PROCESSORS ${np})
  endforeach()
endfunction()

set(spin_up_scene ${PROJECT_SOURCE_DIR}/scenes/spin-up.toml)
# A spin-up the pile cannot follow: too fast (refused as the scene is read), or turning too far
# per step at the final spin (refused once the pile's omega_c is measured, before any step).
spin_up_app_test(rate_too_fast ARGS ${spin_up_scene} --set spin_up.rate=0.5 FAIL
  MESSAGE "--set spin_up.rate=0.5: spin_up.rate: expected a spin-up rate in (0, 0.1] omega_c per dynamical time 1 / omega_c (faster, the pile is kicked rather than spun up), got 0.5")
spin_up_app_test(turn_per_step_too_coarse ARGS ${spin_up_scene} --set pile.settle_steps=0
  --set spin_up.final_spin=100 --set particles.0.count=100 FAIL
  MESSAGE "--set spin_up.final_spin=100: spin_up.final_spin: at 100 omega_c (omega_c = ")
spin_up_app_test(unknown_key ARGS ${spin_up_scene} --set spin_up.rat=0.01 FAIL
  MESSAGE "unknown key 'spin_up.rat' — did you mean 'rate'?")
# A small fly-by: 60 grains settle for 100 steps, then 200 steps of the pass.
spin_up_app_test(flyby_small ARGS ${PROJECT_SOURCE_DIR}/scenes/flyby.toml
  --set particles.0.count=60 --set particles.0.radius=3.5 --set pile.settle_steps=100
  --set time.steps=300 STDOUT_HAS "fly-by: the pass takes" "largest remnant")
# The record and the state continue bit for bit across a restart on another rank count.
if(Python3_Interpreter_FOUND)
  add_test(NAME spin_up.restart_equality
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/spin_up_restart.py
                   --mpiexec ${REGOLITH_MPIEXEC} --app $<TARGET_FILE:spin_up>
                   --scene ${PROJECT_SOURCE_DIR}/scenes/flyby.toml
                   --out ${app_test_out}/spin_up_restart)
  set_tests_properties(spin_up.restart_equality PROPERTIES ENVIRONMENT "${REGOLITH_MPI_TEST_ENV}"
                       LABELS "scene;mpi" TIMEOUT 120 PROCESSORS 2)
endif()
