add_test(NAME cli.end_to_end
         COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/cli_test.sh $<TARGET_FILE:pmech_cli> ${CMAKE_SOURCE_DIR}
                 ${CMAKE_CURRENT_BINARY_DIR}/cli_work)
set_tests_properties(cli.end_to_end PROPERTIES LABELS cli TIMEOUT 600)
add_test(NAME cli.refusals
         COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/refusals_test.sh $<TARGET_FILE:pmech_cli> ${CMAKE_SOURCE_DIR}
                 ${CMAKE_CURRENT_BINARY_DIR}/refusals_work)
set_tests_properties(cli.refusals PROPERTIES LABELS cli TIMEOUT 300)
add_test(NAME cli.signals
         COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/signals_test.sh $<TARGET_FILE:pmech_cli> ${CMAKE_SOURCE_DIR}
                 ${CMAKE_CURRENT_BINARY_DIR}/signals_work)
set_tests_properties(cli.signals PROPERTIES LABELS cli TIMEOUT 300)
add_test(NAME cli.restart
         COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/restart_test.sh $<TARGET_FILE:pmech_cli> ${CMAKE_SOURCE_DIR}
                 ${CMAKE_CURRENT_BINARY_DIR}/restart_work)
set_tests_properties(cli.restart PROPERTIES LABELS cli TIMEOUT 600)
if(PMECH_SANITIZE)
  # ASan's shadow memory needs terabytes of address space, so the refusals' 1 GB bound is the release
  # build's to check; the restart test runs a dozen cases twice each, 5-10 times slower under ASan
  set_tests_properties(cli.refusals PROPERTIES ENVIRONMENT PMECH_NO_VMEM_LIMIT=1)
  set_tests_properties(cli.restart PROPERTIES TIMEOUT 2400)
endif()
