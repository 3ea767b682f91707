# The browser monitor's server (docs/monitor-api.md): Boost.Beast HTTP and WebSocket on a
# monitor::Source, the cell in this process as one (LiveSource), and the `http` server kind
# the runtime registers. Beast is compiled in three files only (http_server.cpp, the
# listener; http_session.cpp and page_session.cpp): it is slow to compile. Beast (of
# roscpp's Boost) and nlohmann-json are header-only, in /usr/include.
file(GLOB MONITOR_SOURCES CONFIGURE_DEPENDS src/monitor/*.cpp)
list(FILTER MONITOR_SOURCES EXCLUDE REGEX "/replay[^/]*\\.cpp$")
add_library(plc_cell_monitor STATIC ${MONITOR_SOURCES})
target_link_libraries(plc_cell_monitor PUBLIC plc_cell_config plc_cell_coverage plc_cell_ladder pthread)
set_target_properties(plc_cell_monitor PROPERTIES POSITION_INDEPENDENT_CODE ON)
# Where the page's files are found when neither the setting nor $PLC_CELL_MONITOR_ASSETS
# says: the source tree this was built from, then the installed package.
target_compile_definitions(plc_cell_monitor PRIVATE
  PLC_CELL_MONITOR_SOURCE_ASSETS="${PROJECT_SOURCE_DIR}/share/monitor"
  PLC_CELL_MONITOR_INSTALLED_ASSETS="${CMAKE_INSTALL_PREFIX}/${CATKIN_PACKAGE_SHARE_DESTINATION}/monitor")
list(APPEND PLC_CELL_SUBSYSTEM_LIBS plc_cell_monitor)

if(CATKIN_ENABLE_TESTING)
  file(GLOB MONITOR_TESTS CONFIGURE_DEPENDS test/monitor/*_test.cpp)
  catkin_add_gtest(monitor_tests test/core/test_main.cpp ${MONITOR_TESTS} test/monitor/client.cpp WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(monitor_tests plc_cell_monitor plc_cell_runtime plc_cell_remote)
  target_compile_definitions(monitor_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(monitor_tests plc_cell_tool)
endif()

# The scan's wake latency with 10 pages open against none (docs/performance.md, "Monitor").
add_executable(bench_monitor_latency bench/monitor_latency.cpp test/monitor/client.cpp)
target_link_libraries(bench_monitor_latency plc_cell_runtime)
target_compile_definitions(bench_monitor_latency PRIVATE PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
