# Scenario tests of a cell: the scenario files, the runner on the virtual timeline, the cell
# as a target in process, JUnit output, and `plc_cell test`. The library sits on the
# runtime (each case runs on a fresh Cell); scenario_runner (the rostest node) links it too.
file(GLOB SCENARIO_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/scenario/*.cpp)
add_library(plc_cell_scenario STATIC ${SCENARIO_SOURCES})
target_link_libraries(plc_cell_scenario PUBLIC plc_cell_runtime)

list(APPEND PLC_CELL_TOOL_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/test_command.cpp ${PROJECT_SOURCE_DIR}/src/cli/scenario_files.cpp)
list(APPEND PLC_CELL_TOOL_LIBS plc_cell_scenario plc_cell_coverage)

if(CATKIN_ENABLE_TESTING)
  file(GLOB SCENARIO_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/scenario/*_test.cpp)
  catkin_add_gtest(scenario_tests test/core/test_main.cpp ${SCENARIO_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(scenario_tests plc_cell_scenario)
  target_compile_definitions(scenario_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(scenario_tests plc_cell_tool)
endif()

# ---- benchmark: virtual seconds per wall second, against plc_cell sim (docs/performance.md)
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(bench_scenario bench/scenario_bench.cpp)
  target_link_libraries(bench_scenario plc_cell_scenario benchmark::benchmark)
  target_compile_definitions(bench_scenario PRIVATE PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endif()
