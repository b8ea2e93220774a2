# The reference-scene apps: granular_gas, dense_ramp and bidisperse, each at CI size,
# run end to end. Weak scaling must give the per-rank grain count times the rank count; strong
# scaling in reproducible mode must give the serial checksum on every rank count; the
# bidisperse scene must run with SOS and hybrid and be refused by NNS. Included by
# tests/apps/CMakeLists.txt (needs Python).

# regolith_reference_app_test(<name> APP <target> NP <n...> [SAME | PER_RANK <grains>]
#                             EXPECT <key=value...> ARGS <app arguments...>)
# Registers apps.<name>.np<n> (or, with SAME, one test apps.<name> comparing the runs on all
# NP): runs the app with compare_runs.py and checks the summaries; @NP@ in EXPECT is the rank
# count; PER_RANK adds particles = grains x ranks (weak scaling).
function(regolith_reference_app_test name)
  cmake_parse_arguments(ARG "SAME" "APP;PER_RANK;CLOSE" "NP;EXPECT;ARGS" ${ARGN})
  set(runner ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/compare_runs.py
      --mpiexec ${REGOLITH_MPIEXEC} --app $<TARGET_FILE:${ARG_APP}> --out ${app_test_out})
  if(ARG_SAME)
    set(tests apps.${name})
    list(GET ARG_NP -1 most)
    add_test(NAME apps.${name}
             COMMAND ${runner} --name apps_${name} --np ${ARG_NP} --same particles checksum
                     --expect ${ARG_EXPECT} -- ${ARG_ARGS})
  elseif(ARG_CLOSE)
    set(tests apps.${name})
    list(GET ARG_NP -1 most)
    add_test(NAME apps.${name}
             COMMAND ${runner} --name apps_${name} --np ${ARG_NP} --same particles --dump
                     --close ${ARG_CLOSE} --expect ${ARG_EXPECT} -- ${ARG_ARGS})
  else()
    set(tests)
    set(most 1)
    foreach(np IN LISTS ARG_NP)
      string(REPLACE "@NP@" ${np} expect "${ARG_EXPECT}")
      if(ARG_PER_RANK)
        math(EXPR grains "${ARG_PER_RANK} * ${np}")
        list(APPEND expect particles=${grains})
      endif()
      add_test(NAME apps.${name}.np${np}
               COMMAND ${runner} --name apps_${name}_np${np} --np ${np} --expect ${expect} --
                       ${ARG_ARGS})
      list(APPEND tests apps.${name}.np${np})
      set(most ${np})
    endforeach()
  endif()
  set_tests_properties(${tests} PROPERTIES ENVIRONMENT "${REGOLITH_MPI_TEST_ENV}"
                       LABELS "scene;mpi" TIMEOUT 120 PROCESSORS ${most})
endfunction()

# Granular gas: weak scaling, a 6^3 box (216 grains) per rank on the 3-D rank grid.
regolith_reference_app_test(granular_gas_weak APP granular_gas NP 1 2 4 PER_RANK 216
  EXPECT scene=granular-gas ranks=@NP@ blocks=@NP@ steps=20 left_domain=0
  ARGS --steps 20 --set granular_gas.per_rank=[6,6,6])
# ... strong scaling: the fixed 12^3 box, two blocks per rank, equal to the serial run.
regolith_reference_app_test(granular_gas_strong APP granular_gas NP 1 2 4 SAME
  EXPECT particles=1728 steps=40
  ARGS --steps 40 --set sync.reproducible=true --set granular_gas.scaling=strong
       --set granular_gas.box=[12,12,12] --set granular_gas.blocks_per_rank=[2,1,1])

# Dense ramp: strong scaling on the 2-D rank grid (8 hcp rows of 8: the y period 4 sqrt(3);
# 4 layers between the walls).
regolith_reference_app_test(dense_ramp_strong APP dense_ramp NP 1 2 4 SAME
  EXPECT particles=256 steps=40 left_domain=0 left_through_walls=0
  ARGS --steps 40 --set sync.reproducible=true --set dense_ramp.scaling=strong
       --set dense_ramp.box=[8,6.928203230275509,4])

# Bidisperse: two building blocks of edge 20, each with a sphere of radius 6 over blocks of
# edge 5 (NNS cannot), hybrid and SOS equal to the serial hybrid run.
set(bidisperse_small --steps 30 --set sync.reproducible=true --set bidisperse.edge=20
    --set bidisperse.large_radius=6 --set bidisperse.building_blocks=[2,1,1])
regolith_reference_app_test(bidisperse_hybrid APP bidisperse NP 1 2 4 SAME
  EXPECT particles=13826 steps=30 left_domain=0 ARGS ${bidisperse_small})
regolith_reference_app_test(bidisperse_sos APP bidisperse NP 1 3 SAME
  EXPECT particles=13826 steps=30 sync=sos ARGS ${bidisperse_small} --set sync.method=sos)

# Two agglomerates (the second paper's scene) at CI size: 2 x 100 grains, 30 steps.
# With the direct sum (bitwise rank-independent) in reproducible mode and the field computed
# every step, every rank count gives the serial state; with the tree it runs and keeps every
# grain. (With update_threshold > 0 a grain that changes rank forces an update, so the update
# steps depend on the layout: reproducible only with threshold 0.)
set(agglomerates_small ${PROJECT_SOURCE_DIR}/scenes/two-agglomerates.toml --steps 30
    --set particles[0].count=100 --set particles[1].count=100
    --set particles[0].radius=540.0 --set particles[1].radius=540.0)
regolith_reference_app_test(two_agglomerates_direct APP regolith NP 1 2 4 SAME
  EXPECT particles=200 steps=30 left_domain=0
  ARGS ${agglomerates_small} --set gravity.self=direct --set sync.reproducible=true
       --set gravity.update_threshold=0.0)
# The same with the field recomputed at an adaptive interval and extrapolated in between: the
# interval follows a median over grains picked by uid, the slopes travel with their grains,
# so every rank count gives the serial state too.
regolith_reference_app_test(two_agglomerates_direct_adaptive APP regolith NP 1 2 4 SAME
  EXPECT particles=200 steps=30 left_domain=0 gravity.interval>1
  ARGS ${agglomerates_small} --set gravity.self=direct --set sync.reproducible=true
       --set gravity.update_threshold=0.0 --set gravity.update_every=adaptive)
# Grains that cross block faces (and ranks) from the first step on, between updates of an
# adaptive interval: each brings its field and slope along, on any layout.
regolith_reference_app_test(migrating_grains_adaptive APP regolith NP 1 2 3 SAME
  EXPECT particles=729 steps=40 gravity.interval>1
  ARGS ${PROJECT_SOURCE_DIR}/tests/apps/scenes/restart_gravity.toml
       --set gravity.update_threshold=0.0 --set gravity.update_every=adaptive)
regolith_reference_app_test(two_agglomerates_tree APP regolith NP 1 2
  EXPECT particles=200 steps=30 left_domain=0 ARGS ${agglomerates_small})
# The tree and the mesh equal the serial run to their tolerance, gravity every step: gravity
# displaces a grain by ~5e-6 m in these 30 steps; the parallel tree's other cell openings
# (force error ~1e-3) move it by 3e-8 m (measured on 2 and 4 ranks), the mesh's PETSc solve
# (rtol 1e-10) by 3e-14 m: asserted below 1e-7 m (2 % of the gravity displacement) and 1e-11 m.
regolith_reference_app_test(two_agglomerates_tree_parallel APP regolith NP 1 2 4 CLOSE 1e-7
  EXPECT particles=200 steps=30 left_domain=0
  ARGS ${agglomerates_small} --set gravity.update_threshold=0.0)
regolith_reference_app_test(two_agglomerates_pm_parallel APP regolith NP 1 2 CLOSE 1e-11
  EXPECT particles=200 steps=30 left_domain=0
  ARGS ${agglomerates_small} --set gravity.self=pm --set gravity.update_threshold=0.0
       --set domain.cells_per_block=[8,8,8])

# Rubble pile around a boulder wider than three blocks at CI size: 2,000 grains;
# hybrid and SOS equal to the serial hybrid run with direct gravity in reproducible mode, on
# 1-8 ranks; NNS refuses it (regolith.rubble_pile_nns_refused).
set(rubble_small ${PROJECT_SOURCE_DIR}/scenes/rubble-pile-boulder.toml --steps 10
    --set particles[1].count=2000 "--set" "particles[1].grain_radius=[12.0,20.0]"
    --set gravity.self=direct --set sync.reproducible=true)
regolith_reference_app_test(rubble_pile_hybrid APP regolith NP 1 2 4 8 SAME
  EXPECT particles=2001 steps=10 left_domain=0 ARGS ${rubble_small})
regolith_reference_app_test(rubble_pile_sos APP regolith NP 1 3 SAME
  EXPECT particles=2001 steps=10 sync=sos ARGS ${rubble_small} --set sync.method=sos)
