# plc_cell explore: random runs of a scenario file's declared inputs against its properties,
# the first violation shrunk to a minimal scenario case. Sits on the scenario layer.
file(GLOB EXPLORE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/explore/*.cpp)
add_library(plc_cell_explore STATIC ${EXPLORE_SOURCES})
target_link_libraries(plc_cell_explore PUBLIC plc_cell_scenario)

list(APPEND PLC_CELL_TOOL_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/explore_command.cpp)
list(APPEND PLC_CELL_TOOL_LIBS plc_cell_explore)

if(CATKIN_ENABLE_TESTING)
  file(GLOB EXPLORE_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/explore/*_test.cpp)
  catkin_add_gtest(explore_tests test/core/test_main.cpp ${EXPLORE_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(explore_tests plc_cell_explore)
  target_compile_definitions(explore_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(explore_tests plc_cell_tool)
endif()
