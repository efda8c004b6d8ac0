# Fuzzing the case loader (label fuzz). With clang: a libFuzzer binary run for a bounded time; with
# other compilers: a stand-alone mutation driver over the same target and seed corpus.
file(GLOB PMECH_FUZZ_SEEDS ${CMAKE_SOURCE_DIR}/examples/*/case.json ${CMAKE_CURRENT_LIST_DIR}/corpus/*.json
     ${CMAKE_SOURCE_DIR}/tests/verification/cases/*.json)
if(CMAKE_C_COMPILER_ID STREQUAL "Clang")
  add_executable(fuzz_case_load ${CMAKE_CURRENT_LIST_DIR}/fuzz_case_load.c)
  target_compile_options(fuzz_case_load PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_options(fuzz_case_load PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_libraries(fuzz_case_load PRIVATE pmech)
  set(PMECH_FUZZ_WORK ${CMAKE_CURRENT_BINARY_DIR}/fuzz_corpus)
  file(MAKE_DIRECTORY ${PMECH_FUZZ_WORK})
  add_test(NAME fuzz.case_load COMMAND fuzz_case_load -max_total_time=60 -timeout=10 -rss_limit_mb=2048
           ${PMECH_FUZZ_WORK} ${CMAKE_CURRENT_LIST_DIR}/corpus)
else()
  add_executable(fuzz_case_load ${CMAKE_CURRENT_LIST_DIR}/fuzz_case_load.c ${CMAKE_CURRENT_LIST_DIR}/fuzz_main.c)
  target_link_libraries(fuzz_case_load PRIVATE pmech)
  add_test(NAME fuzz.case_load COMMAND fuzz_case_load 45 3000000 ${PMECH_FUZZ_SEEDS})
endif()
set_tests_properties(fuzz.case_load PROPERTIES LABELS fuzz TIMEOUT 300)
