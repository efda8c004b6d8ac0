# Fuzz targets (label fuzz): the case loader with pm_sim_create, the Gmsh reader and the driver file.
#
# The seeds are gathered here from the examples and the verification cases, beside the committed
# corpus (tests/fuzz/corpus/<target>: small seeds and every input that once failed).
#
# With PMECH_FUZZ (clang, `make fuzz`): libFuzzer binaries over the instrumented library; each test
# fuzzes for PMECH_FUZZ_SECONDS and keeps what it learns in the build tree. Otherwise: replay binaries
# (fuzz_main.c) run every seed and corpus input once, so each build, and `make asan` under the
# sanitizers, re-checks every input that ever failed; the fuzzing tests then run the sub-build's
# binaries (PMECH_FUZZ_SUBBUILD, below) or are skipped with a note.
set(PMECH_FUZZ_TARGETS case_sim gmsh driver)
set(PMECH_FUZZ_SECONDS 20 CACHE STRING "Seconds each fuzz target runs under ctest")
set(PMECH_FUZZ_SEEDS ${CMAKE_BINARY_DIR}/fuzz-seeds)

# Seeds with names made unique by their directory (many examples call their case case.json).
function(pmech_fuzz_seeds target)
  file(REMOVE_RECURSE ${PMECH_FUZZ_SEEDS}/${target})
  file(MAKE_DIRECTORY ${PMECH_FUZZ_SEEDS}/${target})
  foreach(src ${ARGN})
    get_filename_component(dir ${src} DIRECTORY)
    get_filename_component(dir ${dir} NAME)
    get_filename_component(name ${src} NAME)
    configure_file(${src} ${PMECH_FUZZ_SEEDS}/${target}/${dir}_${name} COPYONLY)
  endforeach()
endfunction()
file(GLOB case_seeds ${CMAKE_SOURCE_DIR}/examples/*/case*.json ${CMAKE_SOURCE_DIR}/tests/verification/cases/*.json)
# the examples' meshes take 0.1-0.4 s each under the sanitizers: replayed, not mutated (the committed
# small meshes hold the same sections)
file(GLOB gmsh_replay ${CMAKE_SOURCE_DIR}/examples/*/*.msh ${CMAKE_SOURCE_DIR}/tests/verification/cases/*.msh)
file(GLOB driver_seeds ${CMAKE_SOURCE_DIR}/examples/triaxial/*.json)
pmech_fuzz_seeds(case_sim ${case_seeds})
pmech_fuzz_seeds(gmsh)
pmech_fuzz_seeds(driver ${driver_seeds})

set(fuzz_src_case_sim fuzz_case_sim.c)
set(fuzz_src_gmsh fuzz_gmsh.c fuzz_memfile.c)
set(fuzz_src_driver fuzz_driver.c fuzz_memfile.c)
set(fuzz_corpus ${CMAKE_CURRENT_LIST_DIR}/corpus)

# fuzz.<target>: libFuzzer for PMECH_FUZZ_SECONDS over the corpus of <build>/fuzz-work/<target>, seeds
# and the committed corpus; a failing input is saved in <build>/fuzz-crashes and fails the test.
function(pmech_fuzz_test build t)
  add_test(NAME fuzz.${t} COMMAND sh ${CMAKE_SOURCE_DIR}/tools/fuzz.sh ${build} ${PMECH_FUZZ_SECONDS} ${t})
  set_tests_properties(fuzz.${t} PROPERTIES LABELS fuzz TIMEOUT 600 SKIP_RETURN_CODE 77 ${ARGN})
endfunction()

if(PMECH_FUZZ)
  add_custom_target(fuzz_targets)
  foreach(t ${PMECH_FUZZ_TARGETS})
    list(TRANSFORM fuzz_src_${t} PREPEND ${CMAKE_CURRENT_LIST_DIR}/ OUTPUT_VARIABLE srcs)
    add_executable(fuzz_${t} ${srcs})
    target_include_directories(fuzz_${t} PRIVATE ${CMAKE_SOURCE_DIR}/src)
    target_compile_definitions(fuzz_${t} PRIVATE FUZZ_CASE_NAME="${CMAKE_SOURCE_DIR}/examples/gmsh_bar/fuzz.json")
    target_link_options(fuzz_${t} PRIVATE -fsanitize=fuzzer)
    target_link_libraries(fuzz_${t} PRIVATE pmech)
    add_dependencies(fuzz_targets fuzz_${t})
    pmech_fuzz_test(${CMAKE_BINARY_DIR} ${t})
  endforeach()
else()
  foreach(t ${PMECH_FUZZ_TARGETS})
    list(TRANSFORM fuzz_src_${t} PREPEND ${CMAKE_CURRENT_LIST_DIR}/ OUTPUT_VARIABLE srcs)
    add_executable(fuzz_${t}_replay ${srcs} ${CMAKE_CURRENT_LIST_DIR}/fuzz_main.c)
    target_include_directories(fuzz_${t}_replay PRIVATE ${CMAKE_SOURCE_DIR}/src)
    target_compile_definitions(fuzz_${t}_replay PRIVATE
                               FUZZ_CASE_NAME="${CMAKE_SOURCE_DIR}/examples/gmsh_bar/fuzz.json")
    target_link_libraries(fuzz_${t}_replay PRIVATE pmech)
    add_test(NAME fuzz.${t}.replay COMMAND fuzz_${t}_replay ${PMECH_FUZZ_SEEDS}/${t} ${fuzz_corpus}/${t} ${${t}_replay})
    set_tests_properties(fuzz.${t}.replay PROPERTIES LABELS fuzz TIMEOUT 300)
  endforeach()
  # The instrumented library is a second, clang build (tools/fuzz-build.sh) made by the first fuzz test
  # rather than with every build: it doubles the compile time, and only the fuzz tests need it.
  set(sub ${CMAKE_BINARY_DIR}/fuzz-clang)
  add_test(NAME fuzz.build COMMAND sh ${CMAKE_SOURCE_DIR}/tools/fuzz-build.sh ${CMAKE_SOURCE_DIR} ${sub})
  set_tests_properties(fuzz.build PROPERTIES LABELS fuzz TIMEOUT 3600 FIXTURES_SETUP pmech_fuzz_build)
  foreach(t ${PMECH_FUZZ_TARGETS})
    pmech_fuzz_test(${sub} ${t} FIXTURES_REQUIRED pmech_fuzz_build)
  endforeach()
endif()
