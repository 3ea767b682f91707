# TRi host link: codec, memory map onto the FBs memory, slave, servers (docs/tri.md).
add_library(plc_cell_tri STATIC
  src/tri/fcs.cpp
  src/tri/frame.cpp
  src/tri/commands.cpp
  src/tri/memory_map.cpp
  src/tri/slave.cpp
  src/tri/server.cpp
  src/tri/server_kind.cpp
  # ---- tri_bridge's bus side: the host-link master (docs/tri.md, "tri_bridge") ----
  src/tri/client.cpp
  src/tri/poll_plan.cpp
  src/tri/bridge_config.cpp
  src/tri/bridge.cpp
  # ---- end of tri_bridge's bus side ----
  )
target_link_libraries(plc_cell_tri PUBLIC plc_cell_config)
set_target_properties(plc_cell_tri PROPERTIES POSITION_INDEPENDENT_CODE ON)

list(APPEND PLC_CELL_SUBSYSTEM_LIBS plc_cell_tri)

# The host link's speed beside FATEK's in the same run (docs/tri.md, "Performance").
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(bench_tri bench/tri_bench.cpp)
  target_link_libraries(bench_tri plc_cell_tri plc_cell_fatek plc_cell_sim benchmark::benchmark)
endif()

if(CATKIN_ENABLE_TESTING)
  file(GLOB TRI_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/tri/*_test.cpp)
  catkin_add_gtest(tri_tests test/core/test_main.cpp ${TRI_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(tri_tests plc_cell_tri plc_cell_fatek plc_cell_sim)  # fatek: the tests' pty and socket helpers
  target_compile_definitions(tri_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(tri_tests plc_cell_tool)
endif()
