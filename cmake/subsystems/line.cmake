# Lines of cells (docs/lines.md): the line file, the wires' model and ends, the line's cells
# on one virtual clock or in real time, and the line as one scenario target. Sits on the
# runtime (each cell a Cell) and the scenario layer (its target); `plc_cell sim --line`,
# `test`, `explore` and `--mutate` take a line through the tool.
file(GLOB LINE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/line/*.cpp)
add_library(plc_cell_line STATIC ${LINE_SOURCES})
target_link_libraries(plc_cell_line PUBLIC plc_cell_scenario)

list(APPEND PLC_CELL_TOOL_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/fresh_target.cpp ${PROJECT_SOURCE_DIR}/src/cli/sim_line.cpp
  ${PROJECT_SOURCE_DIR}/src/cli/run_line.cpp ${PROJECT_SOURCE_DIR}/src/cli/monitor_cells.cpp
  ${PROJECT_SOURCE_DIR}/src/cli/watched_properties.cpp)
list(APPEND PLC_CELL_TOOL_LIBS plc_cell_line)

if(CATKIN_ENABLE_TESTING)
  file(GLOB LINE_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/line/*_test.cpp)
  catkin_add_gtest(line_tests test/core/test_main.cpp ${LINE_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(line_tests plc_cell_line plc_cell_recording)
  target_compile_definitions(line_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(line_tests plc_cell_tool)
endif()

# ---- benchmark: a chain of demo-like cells on one virtual clock (docs/performance.md, "Lines")
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(bench_line bench/line_bench.cpp)
  target_link_libraries(bench_line plc_cell_line benchmark::benchmark)
  target_compile_definitions(bench_line PRIVATE PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endif()

# ---- benchmark: the cost of watching a line's properties (docs/performance.md, "Lines")
add_executable(bench_line_properties bench/line_properties_bench.cpp)
target_link_libraries(bench_line_properties plc_cell_line)
target_compile_definitions(bench_line_properties PRIVATE PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
