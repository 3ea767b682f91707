# Analog and temperature modules, thermal plants, FUN86 TPCTL / FUN30 PID (issue 7).
# Core, no ROS: a library the tool, plc_node and the tests link.
add_library(plc_cell_temp
  src/temp/thermocouple.cpp
  src/temp/rtd.cpp
  src/temp/ntc.cpp
  src/temp/thermal_plant.cpp
  src/temp/temperature_config.cpp
  src/temp/temperature_cell.cpp)
target_link_libraries(plc_cell_temp PUBLIC plc_cell_core)
set_target_properties(plc_cell_temp PROPERTIES POSITION_INDEPENDENT_CODE ON)
list(APPEND PLC_CELL_SUBSYSTEM_LIBS plc_cell_temp)

if(CATKIN_ENABLE_TESTING)
  file(GLOB TEMP_TESTS test/temp/*_test.cpp)
  catkin_add_gtest(temp_tests test/core/test_main.cpp ${TEMP_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(temp_tests plc_cell_temp)
  target_compile_definitions(temp_tests PRIVATE PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endif()
