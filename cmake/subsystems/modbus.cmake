# Modbus subsystem (issue 4): slave servers, master/bridge, gateway. libmodbus does
# all framing; plc_cell_modbus has no ROS in it.
find_package(PkgConfig REQUIRED)
pkg_check_modules(LIBMODBUS REQUIRED IMPORTED_TARGET libmodbus)

add_library(plc_cell_modbus STATIC
  src/modbus/slave_map.cpp
  src/modbus/slave_handler.cpp
  src/modbus/tri_map.cpp
  src/modbus/map_profile.cpp
  src/modbus/rtu_frame.cpp
  src/modbus/tcp_server.cpp
  src/modbus/rtu_server.cpp
  src/modbus/slave_servers.cpp
  src/modbus/server_kind.cpp
  src/modbus/codec.cpp
  src/modbus/bridge_config.cpp
  src/modbus/bridge.cpp
  src/modbus/gateway.cpp
  src/modbus/fun150.cpp)
target_link_libraries(plc_cell_modbus PUBLIC plc_cell_config plc_cell_tri PkgConfig::LIBMODBUS ${YAML_CPP_LIBRARIES})
set_target_properties(plc_cell_modbus PROPERTIES POSITION_INDEPENDENT_CODE ON)
list(APPEND PLC_CELL_SUBSYSTEM_LIBS plc_cell_modbus)

if(CATKIN_ENABLE_TESTING)
  # One binary, run sequentially: several tests use the fixed port 1502.
  file(GLOB MODBUS_TESTS CONFIGURE_DEPENDS test/modbus/*_test.cpp)
  catkin_add_gtest(modbus_tests test/core/test_main.cpp ${MODBUS_TESTS}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(modbus_tests plc_cell_modbus plc_cell_sim)
  target_compile_definitions(modbus_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/modbus_test_tmp"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(modbus_tests plc_cell_tool)
endif()

# ---- modbus_bridge: ROS node over the bus-side Bridge ------------------------
add_executable(modbus_bridge src/ros/modbus_bridge_main.cpp src/ros/modbus_bridge_node.cpp src/ros/bridge_topics.cpp)
target_include_directories(modbus_bridge PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(modbus_bridge plc_cell_modbus ${catkin_LIBRARIES})
add_dependencies(modbus_bridge ${PROJECT_NAME}_generate_messages_cpp)
install(TARGETS modbus_bridge RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest(test/modbus/modbus_bridge.test DEPENDENCIES plc_node modbus_bridge)
endif()

# ---- benchmarks -------------------------------------------------------------
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(bench_modbus bench/modbus_bench.cpp)
  target_link_libraries(bench_modbus plc_cell_modbus plc_cell_sim)
  target_compile_definitions(bench_modbus PRIVATE PLC_CELL_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/modbus_bench_tmp")
endif()
