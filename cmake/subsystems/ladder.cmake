# The IL program drawn as ladder networks, with live power flow (docs/ladder.md). Sits on
# the core alone; the monitor serves its JSON.
find_package(nlohmann_json 3 REQUIRED)
file(GLOB LADDER_SOURCES CONFIGURE_DEPENDS src/ladder/*.cpp)
plc_cell_layer(plc_cell_ladder SOURCES ${LADDER_SOURCES} LINKS plc_cell_core nlohmann_json::nlohmann_json)

if(CATKIN_ENABLE_TESTING)
  file(GLOB LADDER_TESTS CONFIGURE_DEPENDS test/ladder/*_test.cpp)
  catkin_add_gtest(ladder_tests test/core/test_main.cpp ${LADDER_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(ladder_tests plc_cell_ladder)
endif()

install(TARGETS plc_cell_ladder
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
