# Scenario files as rostests (docs/testing-your-cell.md, "The same scenarios as rostests"):
# the scenario_runner node runs a scenario's cases, one gtest test each, on plc_node in
# virtual time through its topics; launch/scenario.test.xml starts both. The runner is
# test tooling, built with the tests (catkin's default), as gtest is a test dependency.
if(CATKIN_ENABLE_TESTING)
  add_executable(scenario_runner src/ros/scenario_runner_main.cpp src/ros/scenario_runner_target.cpp src/ros/scenario_node_link.cpp src/ros/scenario_line_link.cpp
    src/ros/topic_probes.cpp src/ros/counter_topic_probes.cpp src/ros/axis_topic_probes.cpp src/ros/temperature_topic_probes.cpp
    src/ros/server_params.cpp src/ros/topic_plc.cpp src/ros/scenario_real_time.cpp src/ros/scenario_line_real_time.cpp)
  target_include_directories(scenario_runner PRIVATE ${catkin_INCLUDE_DIRS} ${GTEST_INCLUDE_DIRS})
  target_link_libraries(scenario_runner plc_cell_scenario plc_cell_line plc_cell_runtime ${catkin_LIBRARIES} ${GTEST_LIBRARIES})
  add_dependencies(scenario_runner ${PROJECT_NAME}_generate_messages_cpp)
  install(TARGETS scenario_runner RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
  find_package(rostest REQUIRED)
  # The examples' scenario files, as `plc_cell test` runs them (examples/*/*.scenario.yaml).
  # Each written out: scripts/run_tests.py expects a result per add_rostest line.
  add_rostest(test/ros/scenario_conveyor.test DEPENDENCIES plc_node scenario_runner)
  add_rostest(test/ros/scenario_count_up_stop.test DEPENDENCIES plc_node scenario_runner)
  add_rostest(test/ros/scenario_positioning.test DEPENDENCIES plc_node scenario_runner)
  add_rostest(test/ros/scenario_oven.test DEPENDENCIES plc_node scenario_runner)
  add_rostest(test/ros/scenario_pulses.test DEPENDENCIES plc_node scenario_runner)
  add_rostest(test/ros/scenario_two_cells.test DEPENDENCIES plc_node scenario_runner)
  # The hardware scenario in wall-clock time on plc_node in real time (docs/testing-on-hardware.md).
  add_rostest(test/ros/scenario_real_time.test DEPENDENCIES plc_node scenario_runner)
  # The same through fatek_bridge in front of a soft PLC serving FATEK, as on a real PLC.
  add_rostest(test/ros/scenario_real_time_bridge.test DEPENDENCIES fatek_bridge scenario_runner plc_cell_tool)
endif()

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  # plc_node's ~virtual_time/scanned and ~reset, as the runner uses them.
  add_rostest(test/ros/virtual_time_sync.test DEPENDENCIES plc_node)
  # A user's package from the recipe, built and run in a scratch workspace over this one.
  include(${PROJECT_SOURCE_DIR}/cmake/pytest.cmake)
  plc_cell_add_pytest(user_package FILES test/user_package/test_user_package.py
    DEPENDENCIES plc_node scenario_runner plc_cell_generate_messages)
endif()
