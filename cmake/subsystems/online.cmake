# Program changes in RUN (docs/online-change.md): the one path every entry point takes
# (parse, check, compile beside, gate in a child process, swap at a scan boundary, audit
# trail). Below the runtime, which builds one for each cell.
file(GLOB ONLINE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/online/*.cpp)
add_library(plc_cell_online STATIC ${ONLINE_SOURCES})
target_link_libraries(plc_cell_online PUBLIC plc_cell_config)
list(APPEND PLC_CELL_SUBSYSTEM_LIBS plc_cell_online)

list(APPEND PLC_CELL_TOOL_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/gate_command.cpp)

if(CATKIN_ENABLE_TESTING)
  file(GLOB ONLINE_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/online/*_test.cpp)
  catkin_add_gtest(online_tests test/core/test_main.cpp ${ONLINE_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(online_tests plc_cell_runtime)
  target_compile_definitions(online_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(online_tests plc_cell_tool)
  # plc_cell run --watch-program as a user runs it, through the monitor's API.
  include(${PROJECT_SOURCE_DIR}/cmake/pytest.cmake)
  plc_cell_add_pytest(online FILES test/online/test_watch_program.py DEPENDENCIES plc_cell_tool)
endif()

# The scan's wake latency with gates running beside it, against none (docs/performance.md).
add_executable(bench_gate_latency bench/gate_latency.cpp)
target_link_libraries(bench_gate_latency plc_cell_runtime)
target_compile_definitions(bench_gate_latency PRIVATE PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
