# Python tests (pytest) in catkin's run_tests, with JUnit results beside the gtests'
# (scripts/run_tests.py totals pytest-<name>.xml as it does gtest-*.xml and rostest-*.xml).
function(plc_cell_add_pytest name)
  cmake_parse_arguments(_py "" "" "FILES;DEPENDENCIES" ${ARGN})
  set(results ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/pytest-${name}.xml)
  string(REPLACE ";" " " files "${_py_FILES}")
  # catkin's wrapper takes the command as one string (its options would swallow "-m") and
  # runs it in a shell; PLC_CELL_LIB_DIR tells the tests where this workspace's libraries are,
  # PLC_CELL_BUILD_DIR where its build tree is.
  catkin_run_tests_target("pytest" ${name} "pytest-${name}.xml"
    COMMAND "env PLC_CELL_LIB_DIR=${CATKIN_DEVEL_PREFIX}/lib PLC_CELL_BUILD_DIR=${PROJECT_BINARY_DIR} ${PYTHON_EXECUTABLE} -m pytest -q -p no:cacheprovider --junitxml=${results} ${files}"
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    DEPENDENCIES ${_py_DEPENDENCIES})
endfunction()
