# FATEK protocol subsystem (issue 3): codec, slave servers, master client, CLI, bridge node.
add_library(plc_cell_fatek STATIC
  src/fatek/frame.cpp
  src/fatek/protocol.cpp
  src/fatek/slave.cpp
  src/fatek/server.cpp
  src/fatek/server_kind.cpp
  src/fatek/client.cpp
  src/fatek/poll_plan.cpp
  src/fatek/bridge_config.cpp
  src/fatek/bridge.cpp
  src/fatek/clink.cpp
  src/fatek/clink_function.cpp)
target_link_libraries(plc_cell_fatek PUBLIC plc_cell_config)
set_target_properties(plc_cell_fatek PROPERTIES POSITION_INDEPENDENT_CODE ON)

list(APPEND PLC_CELL_TOOL_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/fatek_command.cpp)
list(APPEND PLC_CELL_SUBSYSTEM_LIBS plc_cell_fatek)

if(CATKIN_ENABLE_TESTING)
  file(GLOB FATEK_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/fatek/*_test.cpp)
  catkin_add_gtest(fatek_tests test/core/test_main.cpp ${FATEK_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(fatek_tests plc_cell_fatek plc_cell_sim)
  target_compile_definitions(fatek_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(fatek_tests plc_cell_tool)

  # The mutated-frame fuzz test, built separately with ASan+UBSan from the codec sources.
  catkin_add_gtest(fatek_fuzz_tests test/core/test_main.cpp test/fatek/fuzz/fatek_fuzz.cpp
    src/fatek/frame.cpp src/fatek/protocol.cpp src/core/address.cpp src/core/area.cpp src/core/error.cpp)
  target_include_directories(fatek_fuzz_tests PRIVATE include)
  target_compile_options(fatek_fuzz_tests PRIVATE -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -O1)
  target_link_options(fatek_fuzz_tests PRIVATE -fsanitize=address,undefined)
endif()

# ---- fatek_bridge: a real FATEK PLC on ROS ----------------------------------------
add_executable(fatek_bridge src/ros/fatek_bridge_main.cpp src/ros/fatek_bridge.cpp src/ros/fatek_bridge_services.cpp
  src/ros/memory_services.cpp src/ros/bridge_topics.cpp)
target_include_directories(fatek_bridge PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(fatek_bridge plc_cell_fatek ${catkin_LIBRARIES} ${YAML_CPP_LIBRARIES})
add_dependencies(fatek_bridge ${PROJECT_NAME}_generate_messages_cpp)
install(TARGETS fatek_bridge RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest(test/fatek/fatek_bridge.test DEPENDENCIES fatek_bridge plc_cell_tool)
endif()

# ---- benchmarks (bench/fatek_bench.cpp; docs/fatek.md) ---------------------------
find_package(benchmark QUIET)
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(LIBMODBUS QUIET libmodbus)
endif()
if(benchmark_FOUND AND LIBMODBUS_FOUND)
  add_executable(bench_fatek bench/fatek_bench.cpp)
  target_include_directories(bench_fatek PRIVATE ${LIBMODBUS_INCLUDE_DIRS})
  target_link_libraries(bench_fatek plc_cell_fatek plc_cell_sim benchmark::benchmark ${LIBMODBUS_LIBRARIES})
endif()

if(CATKIN_ENABLE_TESTING)
  add_rostest(test/fatek/plc_node_fatek.test DEPENDENCIES fatek_bridge plc_node)
endif()
