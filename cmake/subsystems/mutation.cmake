# Mutation testing of IL programs (plc_cell test --mutate): mutants of the program, every
# scenario case against each on a fresh cell; the input search that earns "equivalent-suspect"
# runs explore's random runs. Sits on the explore, scenario and coverage layers.
file(GLOB MUTATION_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/mutation/*.cpp)
add_library(plc_cell_mutation STATIC ${MUTATION_SOURCES})
target_link_libraries(plc_cell_mutation PUBLIC plc_cell_explore plc_cell_scenario plc_cell_coverage)

list(APPEND PLC_CELL_TOOL_SOURCES ${PROJECT_SOURCE_DIR}/src/cli/mutate_option.cpp)
list(APPEND PLC_CELL_TOOL_LIBS plc_cell_mutation)

if(CATKIN_ENABLE_TESTING)
  file(GLOB MUTATION_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/mutation/*_test.cpp)
  catkin_add_gtest(mutation_tests test/core/test_main.cpp ${MUTATION_TESTS} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  target_link_libraries(mutation_tests plc_cell_mutation)
  target_compile_definitions(mutation_tests PRIVATE
    PLC_CELL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PLC_CELL_TOOL="$<TARGET_FILE:plc_cell_tool>")
  add_dependencies(mutation_tests plc_cell_tool)
endif()
