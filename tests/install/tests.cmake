# (not in sanitizer builds: the consumer would need the sanitizer runtimes too)
if(NOT PMECH_SANITIZE)
# `make install` works: install into a scratch prefix, then build and run a consumer with pkg-config.
add_test(NAME install.pkg_config
         COMMAND sh -c "rm -rf inst && cmake --install ${CMAKE_BINARY_DIR} --prefix $PWD/inst >/dev/null && PKG_CONFIG_PATH=$PWD/inst/lib/pkgconfig:$PWD/inst/lib64/pkgconfig && export PKG_CONFIG_PATH && ${CMAKE_C_COMPILER} -std=c11 ${CMAKE_CURRENT_LIST_DIR}/consumer.c -o consumer $(pkg-config --cflags --libs --static pmech) && ./consumer"
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(install.pkg_config PROPERTIES LABELS install TIMEOUT 120)
endif()
