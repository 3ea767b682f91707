# The test executables compile at -O1 (-O3 is the product's, CMAKE_BUILD_TYPE Release): they
# are run a few times per build, and at -O3 their compile time, gtest's macros expanded in
# some two hundred files, is a third of the build of make test (docs/testing.md, "The
# suite's own time"). The product's code they test comes from the product's libraries,
# built -O3; the sanitizer builds keep their own flags. Included last, after every target.
get_property(_plc_cell_test_targets DIRECTORY ${PROJECT_SOURCE_DIR} PROPERTY BUILDSYSTEM_TARGETS)
foreach(_t ${_plc_cell_test_targets})
  get_target_property(_type ${_t} TYPE)
  if(_t MATCHES "_tests?$" AND NOT _t MATCHES "_fuzz_tests$|_layer_check$" AND _type STREQUAL "EXECUTABLE")
    target_compile_options(${_t} PRIVATE -O1)
  endif()
endforeach()
