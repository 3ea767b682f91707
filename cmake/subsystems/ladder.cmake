# The IL program drawn as ladder networks, with live power flow (docs/ladder.md). Sits on
# the core alone; the monitor serves its JSON (nlohmann-json: header-only, in /usr/include).
file(GLOB LADDER_SOURCES CONFIGURE_DEPENDS src/ladder/*.cpp)
plc_cell_layer(plc_cell_ladder SOURCES ${LADDER_SOURCES} LINKS plc_cell_core)

if(CATKIN_ENABLE_TESTING)
  file(GLOB LADDER_TESTS CONFIGURE_DEPENDS test/ladder/*_test.cpp)
  catkin_add_gtest(ladder_tests test/core/test_main.cpp ${LADDER_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(ladder_tests plc_cell_ladder plc_cell_sim)
endif()

install(TARGETS plc_cell_ladder
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
