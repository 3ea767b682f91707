# Scenario files on a real PLC (docs/testing-on-hardware.md): `plc_cell test --target` runs
# a file's cases over a FATEK, TRi or Modbus host link in wall-clock time, through the
# scenario layer's wall-clock target, and leaves the PLC as it was found. This library is
# the protocol side: the --target forms and a LinkedPlc per protocol (the monitor's remote
# links for FATEK and the TRi, libmodbus on the FBs map for Modbus), and the polled recording.
file(GLOB HARDWARE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/hardware/*.cpp)
add_library(plc_cell_hardware STATIC ${HARDWARE_SOURCES})
target_link_libraries(plc_cell_hardware PUBLIC plc_cell_scenario plc_cell_remote plc_cell_modbus plc_cell_recording plc_cell_monitor)
set_target_properties(plc_cell_hardware PROPERTIES POSITION_INDEPENDENT_CODE ON)

list(APPEND PLC_CELL_TOOL_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/target_run.cpp ${PROJECT_SOURCE_DIR}/src/cli/target_case.cpp)
list(APPEND PLC_CELL_TOOL_LIBS plc_cell_hardware)

if(CATKIN_ENABLE_TESTING)
  # Against `plc_cell run` standing in for the PLC, over TCP and socat ptys: one binary, run
  # sequentially (each test starts its own stand-in on a free port).
  file(GLOB HARDWARE_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/hardware/*_test.cpp)
  catkin_add_gtest(hardware_tests test/core/test_main.cpp ${HARDWARE_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(hardware_tests plc_cell_hardware plc_cell_runtime)
  target_compile_definitions(hardware_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(hardware_tests plc_cell_tool)
endif()
