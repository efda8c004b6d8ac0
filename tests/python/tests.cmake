# The Python package (python/): its tests against the library just built, and an offline pip install
# from a copy of python/ that bundles that library. Both need a Python with numpy and matplotlib
# (tools/install-deps.sh installs Debian's); the interpreter first on PATH may lack them while the
# distribution's has them, so the first of the two that imports both is used. Without one the tests
# are skipped with a message saying what to install (exit 77).
set(PMECH_PY "")
foreach(py ${Python3_EXECUTABLE} /usr/bin/python3)
  if(NOT PMECH_PY AND EXISTS ${py})
    execute_process(COMMAND ${py} -c "import numpy, matplotlib" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
    if(rc EQUAL 0)
      set(PMECH_PY ${py})
    endif()
  endif()
endforeach()
if(NOT PMECH_PY OR PMECH_SANITIZE)
  # (sanitizer builds: a Python process would need the sanitizer runtimes preloaded)
  set(PMECH_PY_SKIP "echo 'python tests skipped: no python3 with numpy and matplotlib (apt-get install python3-numpy python3-matplotlib, or make deps)'; exit 77")
  add_test(NAME python.package COMMAND sh -c "${PMECH_PY_SKIP}")
  add_test(NAME python.pip_install COMMAND sh -c "${PMECH_PY_SKIP}")
else()
  add_test(NAME python.package COMMAND ${PMECH_PY} ${CMAKE_SOURCE_DIR}/python/tests/test_pmech.py
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(python.package PROPERTIES ENVIRONMENT
    "PMECH_LIBRARY=$<TARGET_FILE:pmech_shared>;PYTHONPATH=${CMAKE_SOURCE_DIR}/python;MPLBACKEND=Agg")
  # pip from a copy of python/ (the checkout stays clean), no index, no build isolation: no network
  add_test(NAME python.pip_install
           COMMAND sh -c "rm -rf pip_src venv && cp -r ${CMAKE_SOURCE_DIR}/python pip_src && rm -rf pip_src/build pip_src/*.egg-info && ${PMECH_PY} -m venv --system-site-packages venv && PMECH_BUILD_DIR=${CMAKE_BINARY_DIR} venv/bin/python -m pip install -q --no-index --no-build-isolation ./pip_src && cd / && env -u PMECH_LIBRARY -u PYTHONPATH ${CMAKE_CURRENT_BINARY_DIR}/venv/bin/python -c \"import pmech, pmech._lib as l; assert l.lib._name.startswith('${CMAKE_CURRENT_BINARY_DIR}/venv'), l.lib._name; c = pmech.Case('${CMAKE_SOURCE_DIR}/examples/dyka_bar/case.json'); c['analysis.end_time'] = 1e-4; r = c.run('${CMAKE_CURRENT_BINARY_DIR}/pip_run'); print('ok', r.info['steps'], 'steps with', l.lib._name)\""
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(python.pip_install PROPERTIES DEPENDS python.package)
endif()
set_tests_properties(python.package python.pip_install PROPERTIES LABELS python TIMEOUT 300 SKIP_RETURN_CODE 77)
