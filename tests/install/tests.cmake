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
set_tests_properties(install.pkg_config PROPERTIES LABELS install TIMEOUT 300)
endif()
