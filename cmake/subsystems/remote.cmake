# Real PLCs in the monitor (docs/monitor-remote.md): a FATEK or TRi PLC polled through its
# host link, as the monitor's Source. Sits on the protocol masters and the Source interface.
file(GLOB REMOTE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/remote/*.cpp)
add_library(plc_cell_remote STATIC ${REMOTE_SOURCES})
target_link_libraries(plc_cell_remote PUBLIC plc_cell_fatek plc_cell_tri)
set_target_properties(plc_cell_remote PROPERTIES POSITION_INDEPENDENT_CODE ON)

list(APPEND PLC_CELL_TOOL_LIBS plc_cell_remote)

if(CATKIN_ENABLE_TESTING)
  file(GLOB REMOTE_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/remote/*_test.cpp)
  catkin_add_gtest(remote_tests test/core/test_main.cpp ${REMOTE_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(remote_tests plc_cell_remote plc_cell_runtime)
  target_compile_definitions(remote_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(remote_tests plc_cell_tool)
endif()
