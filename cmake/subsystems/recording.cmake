# Recorded runs (docs/recordings.md): the recorder `plc_cell sim --record` and
# `plc_cell test --record` use, the file format with its reader, and the recorded run as
# the monitor's source (ReplaySource). Sits on the core and the monitor's Source interface.
find_package(ZLIB REQUIRED)
file(GLOB RECORDING_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/recording/*.cpp)
add_library(plc_cell_recording STATIC ${RECORDING_SOURCES})
target_link_libraries(plc_cell_recording PUBLIC plc_cell_config PRIVATE ZLIB::ZLIB)
set_target_properties(plc_cell_recording PROPERTIES POSITION_INDEPENDENT_CODE ON)

list(APPEND PLC_CELL_TOOL_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/record_option.cpp ${PROJECT_SOURCE_DIR}/src/cli/monitor_command.cpp)
list(APPEND PLC_CELL_TOOL_LIBS plc_cell_recording)

if(CATKIN_ENABLE_TESTING)
  file(GLOB RECORDING_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/recording/*_test.cpp)
  # The monitor's test client drives `plc_cell monitor` as a page would.
  catkin_add_gtest(recording_tests test/core/test_main.cpp ${RECORDING_TESTS} test/monitor/client.cpp
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(recording_tests plc_cell_recording plc_cell_scenario plc_cell_monitor)
  target_compile_definitions(recording_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(recording_tests plc_cell_tool)
endif()
