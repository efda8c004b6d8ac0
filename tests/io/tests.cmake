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
