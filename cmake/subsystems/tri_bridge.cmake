# tri_bridge: a real TRi FMD1616 PLC on ROS (docs/tri.md, "tri_bridge"). The bus side
# (tri/client, poll_plan, bridge_config, bridge) is in plc_cell_tri (cmake/subsystems/tri.cmake).
add_executable(tri_bridge src/ros/tri_bridge_main.cpp src/ros/tri_bridge.cpp src/ros/memory_services.cpp
  src/ros/bridge_topics.cpp)
target_include_directories(tri_bridge PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(tri_bridge plc_cell_tri ${catkin_LIBRARIES} ${YAML_CPP_LIBRARIES})
add_dependencies(tri_bridge ${PROJECT_NAME}_generate_messages_cpp)
install(TARGETS tri_bridge RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  file(GLOB TRI_BRIDGE_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/tri_bridge/*_test.cpp)
  catkin_add_gtest(tri_bridge_tests test/core/test_main.cpp ${TRI_BRIDGE_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(tri_bridge_tests plc_cell_tri plc_cell_fatek plc_cell_sim)  # fatek: the tests' pty helper
  target_compile_definitions(tri_bridge_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(tri_bridge_tests plc_cell_tool)

  find_package(rostest REQUIRED)
  add_rostest(test/tri_bridge/tri_bridge.test DEPENDENCIES tri_bridge plc_cell_tool)
endif()
