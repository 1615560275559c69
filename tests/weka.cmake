# Golden check of the perception models against WEKA itself (Debian package `weka`): the same
# ARFF training and test sets through WEKA's SMO and SMOreg and through our libsvm models.
find_program(TACTILE_JAVA java)
find_file(TACTILE_WEKA_JAR weka.jar PATHS /usr/share/java NO_DEFAULT_PATH)
if(TACTILE_JAVA AND TACTILE_WEKA_JAR)
  tactile_add_test_binary(weka_tests weka tactile_perception)
  target_compile_definitions(weka_tests PRIVATE TACTILE_JAVA="${TACTILE_JAVA}"
                                                TACTILE_WEKA_JAR="${TACTILE_WEKA_JAR}")
  # One process for the whole suite: the simulated data set is built once, not once per test.
  add_test(NAME weka.golden COMMAND weka_tests)
  set_tests_properties(weka.golden PROPERTIES LABELS weka TIMEOUT 300)
else()
  message(WARNING "java or weka.jar not found (tools/setup.sh installs them): no weka tests")
endif()
