# The product's libraries, the ROS layer and the tool compile in unity batches: several
# .cpp files per compiler run. Most of a file's compile time is the headers it includes
# (roscpp and its message templates, Boost.Asio/Beast, yaml-cpp) and the code generated for
# the templates they instantiate, which a batch compiles once instead of once per file: the
# ROS layer's 20 files took 205 CPU seconds one by one and 41 as one batch. That is what
# brings a first `make demo` on a fresh machine to a few minutes (README.md). Names local
# to a file (anonymous namespaces) must therefore be distinct within a library; shared
# constants live in one header. The tests, benchmarks and fuzz builds keep one file per
# compiler run. Included last, after every target exists; -DPLC_CELL_UNITY=OFF turns it off.
option(PLC_CELL_UNITY "compile the product's libraries, nodes and tool in unity batches" ON)
if(PLC_CELL_UNITY)
  get_property(_plc_cell_targets DIRECTORY ${PROJECT_SOURCE_DIR} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(_t ${_plc_cell_targets})
    get_target_property(_type ${_t} TYPE)
    if(_t MATCHES "^plc_cell_" AND NOT _t MATCHES "_layer_check$|_tests$" AND _type MATCHES "_LIBRARY$|^EXECUTABLE$")
      set_target_properties(${_t} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 12)
    endif()
  endforeach()
endif()
