# (not in sanitizer builds: the consumer would need the sanitizer runtimes too)
if(NOT PMECH_SANITIZE)
# `make install` works: install into a scratch prefix, then build a consumer with pkg-config against the
# shared library (as a user would, no extra flags) and against the static one (--static), and run both on
# an installed example; the installed docs must hold the input reference `pmech --help` points to.
set(PMECH_INST "rm -rf inst && cmake --install ${CMAKE_BINARY_DIR} --prefix $PWD/inst >/dev/null && PKG_CONFIG_PATH=$PWD/inst/lib/pkgconfig:$PWD/inst/lib64/pkgconfig && export PKG_CONFIG_PATH")
set(PMECH_EX "inst/share/pmech/examples/dyka_bar/case.json")
add_test(NAME install.pkg_config
         COMMAND sh -c "${PMECH_INST} && ${CMAKE_C_COMPILER} -std=c11 ${CMAKE_CURRENT_LIST_DIR}/consumer.c -o consumer $(pkg-config --cflags --libs pmech) && ldd ./consumer | grep -q 'libpmech.so.0' && ./consumer ${PMECH_EX} && ${CMAKE_C_COMPILER} -std=c11 ${CMAKE_CURRENT_LIST_DIR}/consumer.c -o consumer_static $(pkg-config --cflags --libs --static pmech) && ./consumer_static ${PMECH_EX} && test -f inst/share/doc/pmech/input.md && inst/bin/pmech --help | grep -q 'pmech run'"
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(install.pkg_config PROPERTIES LABELS install TIMEOUT 300 FIXTURES_SETUP pmech_installed)
# The complete example of docs/api.md builds against the installed library and runs: it refuses a
# negative modulus with the case file's message and prints one line per stiffness.
add_test(NAME install.api_example
         COMMAND sh -c "sed -n '/^```c$/,/^```$/p' ${CMAKE_SOURCE_DIR}/docs/api.md | sed '1d;$d' > api_example.c && PKG_CONFIG_PATH=$PWD/inst/lib/pkgconfig:$PWD/inst/lib64/pkgconfig && export PKG_CONFIG_PATH && ${CMAKE_C_COMPILER} -std=c11 -Wall -Wextra -Werror api_example.c -o api_example $(pkg-config --cflags --libs pmech) && ./api_example inst/share/pmech/examples/dyka_bar/case.json > api_example.txt && cat api_example.txt && grep -q 'refused: .*materials.0..youngs_modulus' api_example.txt && [ $(grep -c '^E = ' api_example.txt) -eq 3 ]"
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(install.api_example PROPERTIES LABELS install TIMEOUT 300 FIXTURES_REQUIRED pmech_installed)
endif()
