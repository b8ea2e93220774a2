# Equality with the serial run: the synchronisation scenes of scenes/sync-*.toml run
# 200 steps in reproducible mode on 1, 2, 3, 4 and 8 ranks, with 1, 2 and 8 blocks per rank,
# on a statically refined forest, and with every synchronisation method that can simulate the
# scene; every final state (checksum and --dump CSV, byte for byte) must equal the 1-rank run
# of the scene's own layout. A missed, doubled or misplaced contact, a lost or duplicated
# grain, or a force summed in another order shows up as a different state. Included by
# tests/apps/CMakeLists.txt (needs Python and ${compare}).

set(sync_scenes ${PROJECT_SOURCE_DIR}/scenes)

# regolith_sync_equality(<name> SCENE <file> [ARGS ...] [REFERENCE <other name>]
#                        [FINAL "uid column op value" ...]
#                        [NP1 <case> ...] [NP2 <case> ...] [NP3 <case> ...] [NP4 <case> ...]
#                        [NP8 <case> ...])
# Registers regolith.sync.<name>.np<N> for every NP<N> given: it runs SCENE with ARGS and the
# extra arguments of each <case> ("base" for none, e.g. "--set domain.blocks=[2,2,1]") on N
# ranks and compares each final state with the reference. Without REFERENCE the first NP1
# case must be "base": that run is the reference (the np1 test is the fixture the others
# require); with REFERENCE the runs are compared with the reference of scene test <other
# name>. FINAL checks a value of the final state (compare_runs.py --final).
function(regolith_sync_equality name)
  cmake_parse_arguments(ARG "" "SCENE;REFERENCE" "ARGS;FINAL;NP1;NP2;NP3;NP4;NP8" ${ARGN})
  if(ARG_REFERENCE)
    set(reference ${ARG_REFERENCE})
  else()
    set(reference ${name})
    list(GET ARG_NP1 0 first)
    if(NOT first STREQUAL "base")
      message(FATAL_ERROR "regolith_sync_equality(${name}): the first NP1 case must be base")
    endif()
  endif()
  set(reference_stem ${app_test_out}/sync_${reference}.case0.np1)
  set(finals)
  foreach(check IN LISTS ARG_FINAL)
    list(APPEND finals --final ${check})
  endforeach()
  foreach(np IN ITEMS 1 2 3 4 8)
    if(NOT ARG_NP${np})
      continue()
    endif()
    set(cases)
    foreach(case IN LISTS ARG_NP${np})
      if(case STREQUAL "base")
        list(APPEND cases --case ${np})
      else()
        list(APPEND cases --case "${np} ${case}")
      endif()
    endforeach()
    set(test regolith.sync.${name}.np${np})
    set(ref_args --reference ${reference_stem})
    if(np EQUAL 1 AND NOT ARG_REFERENCE)
      set(ref_args) # this test makes the reference: its first run
    endif()
    add_test(NAME ${test}
             COMMAND ${compare} --name sync_${name} ${cases} ${ref_args}
                     --same particles checksum --expect steps=200 left_domain=0
                     --dump ${finals} -- ${sync_scenes}/${ARG_SCENE} ${ARG_ARGS})
    set(labels scene)
    if(np GREATER 1)
      list(APPEND labels mpi)
    endif()
    set_tests_properties(${test} PROPERTIES ENVIRONMENT "${REGOLITH_MPI_TEST_ENV}"
                         LABELS "${labels}" TIMEOUT 300 PROCESSORS ${np})
    if(np EQUAL 1 AND NOT ARG_REFERENCE)
      set_tests_properties(${test} PROPERTIES FIXTURES_SETUP sync_${name})
    else()
      set_tests_properties(${test} PROPERTIES FIXTURES_REQUIRED sync_${reference})
    endif()
  endforeach()
endfunction()

# Layouts: every rank count on the scene's own layout, and 1, 2 and 8 blocks per rank, a
# refined forest, and each other method on some rank count (comments: blocks per rank of
# each case).
set(one_block "--set domain.blocks=[1,1,1]") # a block that is its own periodic neighbour
# The particles' subdomains are each rank's blocks merged into cuboids by default; "blocks"
# keeps one per block, so that the blocks of a rank exchange shadows among themselves.
set(per_block "--set sync.subdomains=blocks")
set(refined "--set domain.refine=[{min=[0,0,0],max=[4,4,4],level=1}]")

# a) Sparse gas: grains collide and cross block, rank and periodic boundaries; walls in z.
#    Every method (small grains only: NNS applies) must give the same trajectory.
#    With a sync skin (the list of shadows fixed between refreshes, remote shadows along the
#    owners' send lists, UpdateList.hpp) the trajectory is the same too: 64 blocks and one
#    block, hybrid and NNS, on 1, 2, 3 and 8 ranks.
set(skin "--set sync.skin=0.2")
regolith_sync_equality(sparse_gas SCENE sync-sparse-gas.toml
  NP1 base ${one_block} ${skin} "${one_block} ${skin} --set sync.method=nns" # 64, 1
      "--set contact.neighbour_skin=0" ${per_block}    # 64, no Verlet list; 64 subdomains
      "${per_block} --set sync.skin=0"                 # 64 subdomains, no sync skin
  NP2 base "--set domain.blocks=[2,2,1]" ${skin}                       # 32, 2, 32 skin
      "--set contact.neighbour_skin=0.3" "${per_block} --set sync.method=nns" # 32
  NP3 base "--set domain.blocks=[4,3,2]"                               # 21-22, 8
      "--set domain.blocks=[4,3,2] ${skin} --set sync.method=nns"      # 8 NNS skin
      "--set domain.blocks=[4,3,2] ${per_block}"                       # 8 subdomains
  NP4 "--set sync.method=nns" ${refined}                               # 16 NNS, refined
  NP8 base "--set domain.blocks=[2,2,2] --set sync.method=sos"         # 8, 1 SOS
      "${skin} --set sync.method=nns")                                 # 8 NNS skin

#    With van der Waals cohesion (contact.model = "vdw") grains attract across gaps up to the
#    cut-off: pairs apart are contacts too, owned in the gap, and the shadows reach half the
#    cut-off farther; across block, rank and periodic faces the trajectory is the same.
regolith_sync_equality(cohesive_gas SCENE sync-sparse-gas.toml
  ARGS --set contact.model=vdw --set contact.hamaker=0.0015 --set contact.min_separation=0.01
       --set contact.cutoff=0.1
  NP1 base ${one_block} ${skin}                                        # 64, 1, 64 skin
  NP2 base "--set domain.blocks=[2,2,1]" "${per_block} --set sync.method=nns") # 32, 2, NNS

# b) Dense packing under gravity between z walls: long-lived contacts, whose tangential
#    springs travel with the grains.
regolith_sync_equality(dense_packing SCENE sync-dense-packing.toml
  NP1 base ${one_block} "--set sync.skin=0.1" ${per_block}
  NP2 base "--set domain.blocks=[2,2,1]" "--set sync.skin=0.1"
  NP3 base "--set domain.blocks=[4,3,2]"
  NP4 "--set sync.method=sos" ${refined}
  NP8 base "--set domain.blocks=[2,2,2] --set sync.method=nns"
      "--set domain.blocks=[2,2,2] --set sync.method=nns --set sync.skin=0.1")

#    With model C's rolling resistance the rolling springs travel with them too (and the
#    contact loop is the pair-by-pair one: SpringDashpotBatch has no rolling spring).
regolith_sync_equality(dense_packing_rolling_spring SCENE sync-dense-packing.toml
  ARGS --set contact.rolling_friction=0.1 --set contact.rolling_model=spring
  NP1 base ${one_block}
  NP3 base "--set domain.blocks=[4,3,2] --set sync.skin=0.1"
  NP4 "--set sync.method=sos" ${refined})

# c) Bidisperse: the sphere of radius 15 spans 4 x 4 x 4 of the 8 x 8 x 8 blocks and crosses
#    the periodic boundary x = 60 (FINAL: its centre ends near x = 1). Hybrid, and SOS against
#    the hybrid reference: both must give the same trajectory. NNS must refuse it (below).
set(bidisperse_refined
    "--set domain.blocks=[4,4,4] --set domain.refine=[{min=[45,15,15],max=[60,45,45],level=1}]")
regolith_sync_equality(bidisperse_hybrid SCENE sync-bidisperse.toml FINAL "0 x < 5"
  NP1 base ${one_block} ${skin} # 512, 1; skin: grown NNS-class balls, no list (SOS present)
      ${per_block}                                                     # 512 subdomains
  NP2 base "--set domain.blocks=[2,2,1]"                               # 256, 2
  NP3 base "--set domain.blocks=[4,3,2]" ${skin}                       # 170-171, 8
      "${per_block} --set domain.blocks=[4,4,2]"                       # 42-43 subdomains
  NP4 base ${bidisperse_refined}                                       # 128, refined
  NP8 base "--set domain.blocks=[2,2,2]")                              # 64, 1
regolith_sync_equality(bidisperse_sos SCENE sync-bidisperse.toml ARGS --set sync.method=sos
  REFERENCE bidisperse_hybrid FINAL "0 x < 5"
  NP1 base
  NP2 base ${per_block}                                                # 256 subdomains
  NP3 base
  NP4 base ${bidisperse_refined}
  NP8 base "--set domain.blocks=[4,4,4]")                              # 64, 8
