# regolith-render end to end; used by tests/io/CMakeLists.txt as
#   cmake -DMPIEXEC=.. -DAPP=regolith -DRENDER=regolith-render -DXVFB_RUN=.. -DOUT=dir
#         -P RenderCheck.cmake
# Runs 20 steps of the default scene with VTK output every 10 steps on 2 ranks, renders the
# middle entry of the series under xvfb-run and checks the PNG (signature, a plausible size);
# then checks that without a display the tool stops with exit code 2 and its message.
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${MPIEXEC} -n 2 --oversubscribe ${APP} --steps 20 --quiet
                        --set output.vtk_every=10 --output ${OUT}
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "regolith failed (${rc}):\n${err}")
endif()
set(png ${OUT}/step10.png)
execute_process(COMMAND ${XVFB_RUN} -a ${RENDER} ${OUT}/particles.pvd --step 1 --png ${png}
                        --size 400 300
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0 OR NOT out MATCHES "particles_00000010.pvtu \\(time 0.00401")
  message(FATAL_ERROR "regolith-render failed (${rc}):\n${out}\n${err}")
endif()
file(READ ${png} signature LIMIT 8 HEX)
file(SIZE ${png} size)
if(NOT signature STREQUAL "89504e470d0a1a0a" OR size LESS 10000)
  message(FATAL_ERROR "${png}: not a PNG of a picture (signature ${signature}, ${size} bytes)")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=DISPLAY ${RENDER} ${OUT}/particles.pvd
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 2 OR NOT err MATCHES "no X display for VTK's off-screen rendering")
  message(FATAL_ERROR "without a display: exit ${rc}, stderr:\n${err}")
endif()
