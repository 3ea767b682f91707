# The made-up extension of test/extension/ (docs/architecture.md, "How to add an
# extension"): its ROS side built by plc_node's registry path, as a rostest.
if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest_gtest(extension_topics_test test/extension/extension_topics.test test/extension/ticker_topics_test.cpp
    src/ros/extension_ros.cpp src/ros/extension_diagnostics.cpp src/ros/topic_group.cpp)
  target_include_directories(extension_topics_test PRIVATE ${catkin_INCLUDE_DIRS})
  target_link_libraries(extension_topics_test plc_cell_scenario plc_cell_runtime ${catkin_LIBRARIES} ${GTEST_LIBRARIES})
  add_dependencies(extension_topics_test ${PROJECT_NAME}_generate_messages_cpp)
endif()
