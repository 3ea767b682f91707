# Pulse-output positioning: FUN140/141/142/143/147/148, the axes PSO0-PSO3 and their
# profiles; the plc_cell_motion layer, on the counters' edge sources. SoftCell creates the
# motion unit for every cell.
plc_cell_layer(plc_cell_motion LINKS plc_cell_hsc SOURCES
  src/motion/params.cpp
  src/motion/axes_online_check.cpp
  src/motion/program_text.cpp
  src/motion/table_text.cpp
  src/motion/table_regs.cpp
  src/motion/lin_text.cpp
  src/motion/lin_regs.cpp
  src/motion/interpolation.cpp
  src/motion/mpg.cpp
  src/motion/profile.cpp
  src/motion/step_speed.cpp
  src/motion/ramps.cpp
  src/motion/move_plan.cpp
  src/motion/axis.cpp
  src/motion/pulse_pins.cpp
  src/motion/axis_wiring.cpp
  src/motion/switches.cpp
  src/motion/axis_config.cpp
  src/motion/status_registers.cpp
  src/motion/preload.cpp
  src/motion/homing.cpp
  src/motion/positioning.cpp
  src/motion/fun140.cpp
  src/motion/unit_programs.cpp
  src/motion/motion_unit.cpp
  src/motion/motion_functions.cpp
  src/motion/axis_probes.cpp
  src/motion/axes_extension.cpp)

if(CATKIN_ENABLE_TESTING)
  file(GLOB MOTION_TESTS CONFIGURE_DEPENDS test/motion/*_test.cpp)
  catkin_add_gtest(motion_tests test/core/test_main.cpp ${MOTION_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(motion_tests plc_cell_sim)
  target_compile_definitions(motion_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(motion_tests plc_cell_tool)
endif()

# The axes on ROS (plc_node): JointState, status, services, the run action.
list(APPEND PLC_CELL_NODE_SOURCES src/ros/motion_topics.cpp)

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest(test/ros/motion.test DEPENDENCIES plc_node)
  add_rostest(test/ros/motion_plot.test DEPENDENCIES plc_node)
endif()

find_package(benchmark QUIET)
if(benchmark_FOUND AND EXISTS ${PROJECT_SOURCE_DIR}/bench/motion_bench.cpp)
  add_executable(bench_motion bench/motion_bench.cpp)
  target_link_libraries(bench_motion plc_cell_sim benchmark::benchmark)
endif()
