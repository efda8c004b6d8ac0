add_test(NAME cli.material
         COMMAND sh ${CMAKE_CURRENT_LIST_DIR}/material_cli_test.sh $<TARGET_FILE:pmech_cli> ${CMAKE_SOURCE_DIR}
                 ${CMAKE_CURRENT_BINARY_DIR}/material_cli_work)
set_tests_properties(cli.material PROPERTIES LABELS cli TIMEOUT 300)
