# Output files read back by VTK's own reader: write_sample writes an output directory through the
# output API (fixture), then vtk_readback.py checks it. Included from tests/CMakeLists.txt.
add_executable(write_sample ${CMAKE_CURRENT_LIST_DIR}/write_sample.c)
target_link_libraries(write_sample PRIVATE pmech)
target_include_directories(write_sample PRIVATE ${CMAKE_SOURCE_DIR}/src)

set(PMECH_IO_SAMPLE ${CMAKE_CURRENT_BINARY_DIR}/io_sample)
foreach(el quad4 tri3)
  add_test(NAME io.write_sample_${el}
           COMMAND write_sample ${PMECH_IO_SAMPLE}/${el} 1234 ${el})
  set_tests_properties(io.write_sample_${el} PROPERTIES
                       FIXTURES_SETUP io_sample_${el} LABELS io TIMEOUT 60)
  add_test(NAME io.vtk_readback_${el}
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/vtk_readback.py ${PMECH_IO_SAMPLE}/${el} 1234)
  set_tests_properties(io.vtk_readback_${el} PROPERTIES
                       FIXTURES_REQUIRED io_sample_${el} LABELS io TIMEOUT 120)
endforeach()

# The checker must notice a wrong particle count.
add_test(NAME io.vtk_readback_detects_wrong_count
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/vtk_readback.py ${PMECH_IO_SAMPLE}/quad4 1235)
set_tests_properties(io.vtk_readback_detects_wrong_count PROPERTIES
                     FIXTURES_REQUIRED io_sample_quad4 LABELS io WILL_FAIL TRUE TIMEOUT 120)

# A run whose sources and sinks change the particle count between frames (tests/io/flow_case.json,
# frames every 0.01 s): nothing until the resting portion (4 x 2 cells x 4 points = 32) appears at
# 0.015 s, the falling one (2 x 1 x 4 = 8) at 0.025 s; moving at 10 m/s, all of the latter has crossed
# the outlet 0.05 m below it by 0.04 s (its lowest points reach it at 0.0321 s, its highest leave it at
# 0.0379 s). VTK must read every frame, the empty ones too.
set(PMECH_IO_FLOW ${CMAKE_CURRENT_BINARY_DIR}/io_flow)
add_test(NAME io.write_flow
         COMMAND $<TARGET_FILE:pmech_cli> run ${CMAKE_CURRENT_LIST_DIR}/flow_case.json -o ${PMECH_IO_FLOW} --overwrite --quiet)
set_tests_properties(io.write_flow PROPERTIES FIXTURES_SETUP io_flow LABELS io TIMEOUT 60)
add_test(NAME io.vtk_readback_flow
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/vtk_readback.py ${PMECH_IO_FLOW} 0,0,32,40,32,32)
set_tests_properties(io.vtk_readback_flow PROPERTIES FIXTURES_REQUIRED io_flow LABELS io TIMEOUT 120)
add_test(NAME io.vtk_readback_flow_detects_wrong_counts
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/vtk_readback.py ${PMECH_IO_FLOW} 0,0,32,32,32,32)
set_tests_properties(io.vtk_readback_flow_detects_wrong_counts PROPERTIES
                     FIXTURES_REQUIRED io_flow LABELS io WILL_FAIL TRUE TIMEOUT 120)
