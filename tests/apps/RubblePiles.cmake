# The rubble-pile app spin_up end to end (docs/guide/rubble-piles.md): its bad input refused
# with one message on 1 and 4 ranks, and a small fly-by run. Included by
# tests/apps/CMakeLists.txt.

set(spin_up_scene ${PROJECT_SOURCE_DIR}/scenes/spin-up.toml)
# A spin-up the pile cannot follow: too fast (refused as the scene is read), or turning too far
# per step at the final spin (refused once the pile's omega_c is measured, before any step).
regolith_app_test(rate_too_fast APP spin_up ARGS ${spin_up_scene} --set spin_up.rate=0.5 FAIL
  MESSAGE "--set spin_up.rate=0.5: spin_up.rate: expected a spin-up rate in (0, 0.1] omega_c per dynamical time 1 / omega_c (faster, the pile is kicked rather than spun up), got 0.5")
regolith_app_test(turn_per_step_too_coarse APP spin_up ARGS ${spin_up_scene}
  --set pile.settle_steps=0
  --set spin_up.final_spin=100 --set particles.0.count=100 FAIL EXIT_CODE 2
  MESSAGE "--set spin_up.final_spin=100: spin_up.final_spin: at 100 omega_c (omega_c = ")
regolith_app_test(unknown_key APP spin_up ARGS ${spin_up_scene} --set spin_up.rat=0.01 FAIL
  MESSAGE "unknown key 'spin_up.rat' — did you mean 'rate'?")
# A small fly-by: 60 grains settle for 100 steps, then 200 steps of the pass.
regolith_app_test(flyby_small APP spin_up ARGS ${PROJECT_SOURCE_DIR}/scenes/flyby.toml
  --set particles.0.count=60 --set particles.0.radius=3.5 --set pile.settle_steps=100
  --set time.steps=300 --output ${app_test_out}/spin_up_flyby_small_@NP@ STDOUT_HAS "fly-by: the pass takes" "largest remnant")
# A run shorter than the settling says so instead of ending silently.
regolith_app_test(ends_before_settled APP spin_up ARGS ${PROJECT_SOURCE_DIR}/scenes/flyby.toml
  --set particles.0.count=60 --set particles.0.radius=3.5 --set pile.settle_steps=100
  --set time.steps=50 --output ${app_test_out}/spin_up_ends_before_settled_@NP@
  STDOUT_HAS "rubble pile: nothing recorded: the run ended before the pile settled (pile.settle_steps = 100)")
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
