# Analog and temperature modules, thermal plants, FUN86 TPCTL: the plc_cell_temp layer,
# no ROS. SoftCell installs them for every cell.
plc_cell_layer(plc_cell_temp LINKS plc_cell_config SOURCES
  src/temp/thermocouple.cpp
  src/temp/rtd.cpp
  src/temp/ntc.cpp
  src/temp/thermal_plant.cpp
  src/temp/temperature_config.cpp
  src/temp/temperature_cell.cpp
  src/temp/analog_codes.cpp
  src/temp/analog_modules.cpp
  src/temp/tpctl.cpp
  src/temp/pid.cpp
  src/temp/temp_functions.cpp
  src/temp/rtc_calendar.cpp
  src/temp/rtc_calibration.cpp
  src/temp/rtc.cpp
  src/temp/linear_conversion.cpp
  src/temp/hspwm.cpp
  src/temp/pwmda.cpp
  src/temp/fb_tc_scaling.cpp
  src/temp/tpctl_loop.cpp
  src/temp/fb_modules.cpp
  src/temp/fb_measure.cpp
  src/temp/fb_functions.cpp
  src/temp/sensor_signal.cpp
  src/temp/loop_settings.cpp
  src/temp/module_probes.cpp
  src/temp/modules_extension.cpp
  src/temp/analog_conditioning.cpp)

if(CATKIN_ENABLE_TESTING)
  file(GLOB TEMP_TESTS CONFIGURE_DEPENDS test/temp/*_test.cpp)
  catkin_add_gtest(temp_tests test/core/test_main.cpp ${TEMP_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(temp_tests plc_cell_sim)
  target_compile_definitions(temp_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(temp_tests plc_cell_tool)
endif()

# make bench: 64 temperature channels + 16 PID loops against a 1 ms scan.
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(bench_temp bench/temp_bench.cpp)
  target_link_libraries(bench_temp plc_cell_sim benchmark::benchmark)
endif()

# plc_node: temperatures on topics, /diagnostics per module, ~set_pid_loop.
list(APPEND PLC_CELL_NODE_SOURCES src/ros/temperature_ros.cpp)

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest(test/ros/temperature.test DEPENDENCIES plc_node)
endif()
