# Reliability subsystem (issue 8): retentive memory that survives restarts and crashes.
add_library(plc_cell_persist STATIC
  src/persist/crc32.cpp
  src/persist/retentive_image.cpp
  src/persist/slot_file.cpp
  src/persist/persister.cpp)
find_package(ZLIB REQUIRED)
target_link_libraries(plc_cell_persist PUBLIC plc_cell_config PRIVATE ZLIB::ZLIB)
set_target_properties(plc_cell_persist PROPERTIES POSITION_INDEPENDENT_CODE ON)
list(APPEND PLC_CELL_SUBSYSTEM_LIBS plc_cell_persist)
# SIGINT/SIGTERM as a signalfd event: the clean stop of plc_cell run and plc_node.
list(APPEND PLC_CELL_TOOL_SOURCES ${PROJECT_SOURCE_DIR}/src/io/stop_signal.cpp)
list(APPEND PLC_CELL_NODE_SOURCES ${PROJECT_SOURCE_DIR}/src/io/stop_signal.cpp)

if(CATKIN_ENABLE_TESTING)
  file(GLOB RELIABILITY_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/reliability/*_test.cpp)
  catkin_add_gtest(reliability_tests test/core/test_main.cpp ${RELIABILITY_TESTS} src/io/stop_signal.cpp WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(reliability_tests plc_cell_runtime)
  target_compile_definitions(reliability_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(reliability_tests plc_cell_tool)
endif()

# ---- libFuzzer targets (test/fuzz/): a clang sub-build, run briefly by fuzz_tests -------
# Test tooling only: built with the tests (catkin_make tests, make build), never by a plain
# catkin build, which then needs no clang. make installs clang (DEB_PACKAGES); a tree
# configured without it gets a fuzz_tests that fails and says so, never one that skips.
if(CATKIN_ENABLE_TESTING)
  include(ExternalProject)
  find_program(PLC_CELL_CLANGXX NAMES clang++ clang++-14)
  if(PLC_CELL_CLANGXX)
    set(PLC_CELL_FUZZ_DIR ${CMAKE_CURRENT_BINARY_DIR}/fuzz)
    ExternalProject_Add(plc_cell_fuzzers
      SOURCE_DIR ${PROJECT_SOURCE_DIR}/test/fuzz
      BINARY_DIR ${PLC_CELL_FUZZ_DIR}
      CMAKE_ARGS -DCMAKE_CXX_COMPILER=${PLC_CELL_CLANGXX} -DCMAKE_BUILD_TYPE=RelWithDebInfo
      BUILD_ALWAYS ON
      EXCLUDE_FROM_ALL ON
      INSTALL_COMMAND "")
    catkin_add_gtest(fuzz_tests test/core/test_main.cpp test/reliability/fuzz/fuzz_runs.cpp)
    target_compile_definitions(fuzz_tests PRIVATE
      PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}" PLC_CELL_FUZZ_DIR="${PLC_CELL_FUZZ_DIR}")
    add_dependencies(fuzz_tests plc_cell_fuzzers)
  else()
    catkin_add_gtest(fuzz_tests test/core/test_main.cpp test/reliability/fuzz/no_clang.cpp)
  endif()
endif()

if(CATKIN_ENABLE_TESTING)
  add_rostest(test/reliability/two_cells.test DEPENDENCIES plc_node)
endif()

# plc_node's virtual-time mode (deterministic replay of bags).
if(CATKIN_ENABLE_TESTING)
  add_rostest(test/reliability/replay.test DEPENDENCIES plc_node)
  add_rostest(test/reliability/node_restart.test DEPENDENCIES plc_node)
endif()

# make soak (not part of make test, test tooling only): see docs/reliability.md.
if(CATKIN_ENABLE_TESTING)
  add_executable(plc_cell_soak test/reliability/soak/soak_main.cpp)
  target_link_libraries(plc_cell_soak plc_cell_fatek plc_cell_modbus plc_cell_persist plc_cell_sim)
  target_compile_definitions(plc_cell_soak PRIVATE PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(plc_cell_soak plc_cell_tool)
endif()

# ---- hostile clients against `plc_cell run` (test/reliability/abuse/) ----------
if(CATKIN_ENABLE_TESTING)
  file(GLOB ABUSE_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/reliability/abuse/*_test.cpp)
  catkin_add_gtest(abuse_tests test/core/test_main.cpp ${ABUSE_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(abuse_tests plc_cell_fatek plc_cell_modbus plc_cell_sim)
  target_compile_definitions(abuse_tests PRIVATE PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(abuse_tests plc_cell_tool)
endif()
