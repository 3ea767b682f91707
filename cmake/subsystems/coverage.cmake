# Rung coverage of IL programs: what a scenario-test run exercised, summed over its cases,
# as text, JSON and an HTML page. Sits on the core alone; the interpreter records into it
# only while a Recorder is attached.
file(GLOB COVERAGE_SOURCES CONFIGURE_DEPENDS src/coverage/*.cpp)
plc_cell_layer(plc_cell_coverage SOURCES ${COVERAGE_SOURCES} LINKS plc_cell_core)

if(CATKIN_ENABLE_TESTING)
  file(GLOB COVERAGE_TESTS CONFIGURE_DEPENDS test/coverage/*_test.cpp)
  catkin_add_gtest(coverage_tests test/core/test_main.cpp ${COVERAGE_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(coverage_tests plc_cell_coverage)
endif()

install(TARGETS plc_cell_coverage
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
