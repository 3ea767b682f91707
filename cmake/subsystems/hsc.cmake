# High-speed counters, timers and their interrupt sources: the plc_cell_hsc layer, a
# source of the cell's scheduler (plc_cell_timeline). The soft cell
# creates the unit for every program (time-base interrupts need no configuration).
plc_cell_layer(plc_cell_hsc LINKS plc_cell_config plc_cell_timeline SOURCES
  src/hsc/count_rule.cpp
  src/hsc/decoding.cpp
  src/hsc/pulse_source.cpp
  src/hsc/pulse_meter.cpp
  src/hsc/pulse_measurement.cpp
  src/hsc/hsc_config.cpp
  src/hsc/hsc_unit.cpp
  src/hsc/input_pins.cpp
  src/hsc/terminal_edges.cpp
  src/hsc/pulse_train.cpp
  src/hsc/count_decoder.cpp
  src/hsc/hsc_counter.cpp
  src/hsc/hs_timer.cpp
  src/hsc/edge_interrupts.cpp
  src/hsc/measured_input.cpp
  src/hsc/output_image.cpp
  src/hsc/hsc_functions.cpp
  src/hsc/input_filter.cpp
  src/hsc/scan_debounce.cpp
  src/hsc/counter_probes.cpp
  src/hsc/counters_extension.cpp)

if(CATKIN_ENABLE_TESTING)
  file(GLOB HSC_TESTS CONFIGURE_DEPENDS test/hsc/*_test.cpp)
  catkin_add_gtest(hsc_tests test/core/test_main.cpp ${HSC_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(hsc_tests plc_cell_sim)
  target_compile_definitions(hsc_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(hsc_tests plc_cell_tool)
endif()

find_package(benchmark QUIET)
if(benchmark_FOUND AND EXISTS ${PROJECT_SOURCE_DIR}/bench/hsc_bench.cpp)
  add_executable(bench_hsc bench/hsc_bench.cpp)
  target_link_libraries(bench_hsc plc_cell_sim benchmark::benchmark)
endif()

# The counters on ROS topics and services (plc_node).
list(APPEND PLC_CELL_NODE_SOURCES src/ros/counter_topics.cpp src/ros/pulse_topics.cpp)

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest(test/ros/counters.test DEPENDENCIES plc_node)
  add_rostest(test/ros/pulses.test DEPENDENCIES plc_node)
endif()
