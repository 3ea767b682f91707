# plc_node and the bridges as nodelets (docs/nodelets.md): one shared library that the
# nodelet manager loads (nodelet_plugins.xml). The static layers it links go into a shared
# object, so they are built position-independent.
# Debian's pluginlib (under nodelet) is built with ament, whose CMake runs Python: the
# workspace's Python, not a python3 found first on PATH without ament_package.
if(PYTHON_EXECUTABLE AND NOT Python3_EXECUTABLE)
  set(Python3_EXECUTABLE ${PYTHON_EXECUTABLE})
endif()
find_package(nodelet REQUIRED)
find_package(pluginlib REQUIRED)
set_target_properties(plc_cell_runtime plc_cell_comm ${PLC_CELL_SUBSYSTEM_LIBS} plc_cell_line plc_cell_scenario
  PROPERTIES POSITION_INDEPENDENT_CODE ON)
add_library(plc_cell_nodelets SHARED src/ros/nodelets.cpp
  src/ros/fatek_bridge.cpp src/ros/fatek_bridge_services.cpp src/ros/bridge_topics.cpp src/ros/tri_bridge.cpp
  src/ros/modbus_bridge_node.cpp src/ros/monitor_nodelet.cpp src/ros/line_node.cpp src/ros/line_wire_topics.cpp src/ros/line_virtual_time.cpp)
target_include_directories(plc_cell_nodelets PRIVATE ${catkin_INCLUDE_DIRS} ${nodelet_INCLUDE_DIRS} ${pluginlib_INCLUDE_DIRS})
target_link_libraries(plc_cell_nodelets plc_cell_plc_node plc_cell_fatek plc_cell_tri plc_cell_modbus plc_cell_line
  ${nodelet_LIBRARIES} ${pluginlib_LIBRARIES} ${catkin_LIBRARIES} ${YAML_CPP_LIBRARIES})
add_dependencies(plc_cell_nodelets ${PROJECT_NAME}_generate_messages_cpp)
install(TARGETS plc_cell_nodelets LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
# The line nodelet's class in a process of its own, as plc_node is plc_cell/PlcNodelet's.
add_executable(line_node src/ros/line_node_main.cpp src/ros/line_node.cpp src/ros/line_wire_topics.cpp src/ros/line_virtual_time.cpp)
target_link_libraries(line_node plc_cell_plc_node plc_cell_line)
install(TARGETS line_node RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
# The workspace's copy of the package links its files (Makefile, ws-src): install the file the link names.
get_filename_component(PLC_CELL_NODELET_XML ${PROJECT_SOURCE_DIR}/nodelet_plugins.xml REALPATH)
install(FILES ${PLC_CELL_NODELET_XML} DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest(test/ros/nodelets.test DEPENDENCIES plc_cell_nodelets)
  # A line of cells (docs/lines.md, "On ROS"): in one manager, and split over two.
  add_rostest(test/ros/line.test DEPENDENCIES plc_cell_nodelets scenario_runner)
  add_rostest(test/ros/line_split.test DEPENDENCIES plc_cell_nodelets line_node scenario_runner)
  # The line's hardware scenario through the scenario_runner, in one manager and split.
  add_rostest(test/ros/scenario_line.test DEPENDENCIES plc_cell_nodelets scenario_runner)
  add_rostest(test/ros/scenario_line_split.test DEPENDENCIES plc_cell_nodelets line_node scenario_runner)
  # The line in virtual time: its cells' topics against plc_cell sim of the same line file, and
  # the line's scenario through the scenario_runner on its one clock.
  add_rostest(test/ros/line_virtual_time.test DEPENDENCIES plc_cell_nodelets plc_cell_tool)
  add_rostest(test/ros/scenario_line_virtual_time.test DEPENDENCIES plc_cell_nodelets scenario_runner)
endif()
