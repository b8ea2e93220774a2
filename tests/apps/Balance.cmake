# Dynamic load balance: runs in reproducible mode whose blocks move between ranks during the
# run (balance.every = 10 or 2, threshold = 1: a new cut whenever a better one exists) must
# end in the serial run's state, byte for byte, having moved their blocks at least once: the
# settling gas (its load falls into the bottom blocks) on 2, 3, 4, 8 and 27 ranks; direct self-gravity with
# update_threshold > 0 (the cached field follows its grains to their new ranks) on 2 and 3.
# The blocks split too where one outweighs a rank's share (balance.split_levels, "auto"): the
# settling gas on 27 ranks, the cold collapse on one block below.
# Included by tests/apps/CMakeLists.txt (needs Python and ${compare}).

# regolith_balance_equality(<name> EVERY <steps> RANKS <np> ... ARGS <app arguments>)
function(regolith_balance_equality name)
  cmake_parse_arguments(ARG "" "EVERY" "RANKS;ARGS;EXPECT" ${ARGN})
  set(expects --expect balance.rebalances>0)
  foreach(e IN LISTS ARG_EXPECT)
    list(APPEND expects --expect ${e})
  endforeach()
  set(app_args ${ARG_ARGS})
  add_test(NAME regolith.balance.${name}.np1
           COMMAND ${compare} --name balance_${name} --np 1 --expect balance.rebalances=0
                   --dump -- ${app_args})
  set_tests_properties(regolith.balance.${name}.np1 PROPERTIES FIXTURES_SETUP balance_${name}
                       ENVIRONMENT "${REGOLITH_MPI_TEST_ENV}" LABELS "scene" TIMEOUT 60)
  foreach(np IN LISTS ARG_RANKS)
    set(test regolith.balance.${name}.np${np})
    add_test(NAME ${test}
             COMMAND ${compare} --name balance_${name}
                     --case "${np} --set balance.every=${ARG_EVERY} --set balance.threshold=1"
                     --reference ${app_test_out}/balance_${name}.np1 --same particles checksum
                     ${expects} --dump -- ${app_args})
    set_tests_properties(${test} PROPERTIES FIXTURES_REQUIRED balance_${name}
                         ENVIRONMENT "${REGOLITH_MPI_TEST_ENV}" LABELS "scene;mpi"
                         TIMEOUT 120 PROCESSORS 2)
  endforeach()
endfunction()

regolith_balance_equality(settling EVERY 10 RANKS 2 3 4 8 27 ARGS
  ${PROJECT_SOURCE_DIR}/scenes/settling-gas.toml --set time.steps=300
  --set sync.reproducible=true)
# The cold collapse on one block: it splits where the cloud gathers (at the start, where it
# holds every rank's share, and as the cloud collapses); the direct sum's field in canonical
# order keeps every bit.
regolith_balance_equality(split EVERY 10 RANKS 3 8 EXPECT balance.splits>8 ARGS
  ${PROJECT_SOURCE_DIR}/scenes/cold-collapse.toml --set time.steps=100
  --set domain.blocks=[1,1,1] --set sync.reproducible=true)
regolith_balance_equality(gravity EVERY 2 RANKS 2 3 ARGS
  ${bad}/restart_gravity.toml --set domain.blocks=[4,4,4])

# A checkpoint written after rebalances at step AT on FROM ranks, restarted on TO ranks (which
# cuts its blocks by the load at once, then goes on rebalancing), ends in the state of the
# serial run of regolith_balance_equality(<name>).
# regolith_balance_restart(<name> FROM <np> TO <np> AT <step> EXPECT <key>... ARGS <app args>)
function(regolith_balance_restart name)
  cmake_parse_arguments(ARG "" "FROM;TO;AT" "EXPECT;ARGS" ${ARGN})
  set(dir ${app_test_out}/balance_${name}_restart)
  set(rebalancing --set balance.every=10 --set balance.threshold=1)
  string(JOIN " " rebalancing ${rebalancing})
  math(EXPR padded "100000000 + ${ARG_AT}")
  string(SUBSTRING ${padded} 1 8 padded)
  set(expects)
  foreach(e IN LISTS ARG_EXPECT)
    list(APPEND expects --expect ${e})
  endforeach()
  add_test(NAME regolith.balance.${name}_restart
           COMMAND ${compare} --name balance_${name}_restart
                   --case "${ARG_FROM} ${rebalancing} --set output.checkpoint_every=${ARG_AT} --output ${dir}"
                   --case "${ARG_TO} ${rebalancing} --restart ${dir}/checkpoint_${padded}.h5 --output ${dir}"
                   --reference ${app_test_out}/balance_${name}.np1 --same particles checksum
                   ${expects} --dump -- ${ARG_ARGS})
  set_tests_properties(regolith.balance.${name}_restart PROPERTIES
                       FIXTURES_REQUIRED balance_${name} ENVIRONMENT "${REGOLITH_MPI_TEST_ENV}"
                       LABELS "scene;mpi" TIMEOUT 120 PROCESSORS 2)
endfunction()

regolith_balance_restart(settling FROM 3 TO 2 AT 150 EXPECT balance.rebalances>0 ARGS
  ${PROJECT_SOURCE_DIR}/scenes/settling-gas.toml --set time.steps=300
  --set sync.reproducible=true)
# The cold collapse's split blocks: written on 8 ranks after splits, restarted on 3 (the
# scene's block, split again at the start's cut).
regolith_balance_restart(split FROM 8 TO 3 AT 50 EXPECT balance.splits>8 ARGS
  ${PROJECT_SOURCE_DIR}/scenes/cold-collapse.toml --set time.steps=100
  --set domain.blocks=[1,1,1] --set sync.reproducible=true)

# ParaView sees the blocks change owner: blocks.pvd's pieces at the start and the end.
add_test(NAME regolith.balance.blocks_vtk
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/balance_vtk_check.py
                 --mpiexec ${REGOLITH_MPIEXEC} --app $<TARGET_FILE:regolith>
                 --scene ${PROJECT_SOURCE_DIR}/scenes/settling-gas.toml --out ${app_test_out})
set_tests_properties(regolith.balance.blocks_vtk PROPERTIES ENVIRONMENT "${REGOLITH_MPI_TEST_ENV}"
                     LABELS "scene;mpi" TIMEOUT 60 PROCESSORS 2)
