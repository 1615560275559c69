# The Python module's pytest tests (tests/python), one CTest test per file, label `python`; run
# with the interpreter the module was built for, the module found through PYTHONPATH in the
# build tree. Not defined when the module is not built (python/CMakeLists.txt says when).
if(NOT TARGET tactile_python)
  return()
endif()
file(GLOB tactile_python_tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/python/test_*.py)
foreach(test_file ${tactile_python_tests})
  get_filename_component(test_name ${test_file} NAME_WE)
  string(REPLACE "test_" "" test_name ${test_name})
  add_test(NAME python.${test_name}
           COMMAND ${Python3_EXECUTABLE} -m pytest -q -p no:cacheprovider
                   --basetemp=${CMAKE_CURRENT_BINARY_DIR}/python-tmp-${test_name} ${test_file})
  set_tests_properties(python.${test_name} PROPERTIES
    LABELS python TIMEOUT 600
    ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1;PYTHONPATH=${TACTILE_PYTHON_MODULE_DIR};TACTILE_CLI=$<TARGET_FILE:tactile>;TACTILE_TEST_DATA_DIR=${TACTILE_TEST_DATA_DIR};TACTILE_SOURCE_DIR=${PROJECT_SOURCE_DIR};TACTILE_BUILD_DIR=${PROJECT_BINARY_DIR};TACTILE_E2E_DEMO_DIR=${TACTILE_E2E_DEMO_DIR};TACTILE_PYTHON_INSTALL_DIR=${TACTILE_PYTHON_INSTALL_DIR};MPLBACKEND=Agg")
endforeach()
# The README's example runs on the demo's strain movie.
set_tests_properties(python.readme PROPERTIES FIXTURES_REQUIRED demo_run)
# Installs the whole project into a temporary prefix, like package.consumer.
set_tests_properties(python.install PROPERTIES LABELS "python;package")
# Compares the map keywords on the demo's strain movie.
set_tests_properties(python.options PROPERTIES FIXTURES_REQUIRED demo_run)
set_tests_properties(python.live PROPERTIES FIXTURES_REQUIRED demo_run)
