#pragma once
// A soft PLC on a virtual clock: tests step N scans of T ms and read memory.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "plc_cell/core/address.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/native/engine_choice.h"
#include "plc_cell/core/plc.h"

namespace plc_cell {

class PlcFixture : public ::testing::Test {
 protected:
  // Subsystem tests pass a table with their FUN instructions.
  explicit PlcFixture(FunctionTable functions = FunctionTable::with_core_functions()) : plc(std::move(functions)) {}

  void load(const std::string& text) {
    plc.load_program_text(text, "test.il");
    ASSERT_TRUE(plc.set_mode(RunMode::Run));
  }
  // Scans at now, now + period, ...; after it, now has advanced by n * period.
  void scans(int n, uint64_t period_us = 1000) {
    for (int i = 0; i < n; ++i) {
      plc.scan(now_us);
      now_us += period_us;
    }
  }
  void input(uint32_t x, bool v) { plc.set_input(x, v); }
  uint32_t get(const std::string& a) { return plc.read(parse_address(a), 1).at(0); }
  int32_t sget(const std::string& a) { return static_cast<int16_t>(get(a)); }
  void put(const std::string& a, uint32_t v) { plc.write(parse_address(a), {v}); }

  Plc plc;
  uint64_t now_us = 0;
};

// The instructions' tests run on both engines: on native, the default, and on the
// interpreter, which keeps its own tests. A suite of this fixture is instantiated with
// PLC_CELL_ON_BOTH_ENGINES(Suite); its tests are named Suite.Test/native and
// Suite.Test/interpreter, so --gtest_filter='Suite.*' runs both.
class BothEnginesFixture : public PlcFixture, public ::testing::WithParamInterface<EngineChoice> {
 protected:
  explicit BothEnginesFixture(FunctionTable functions = FunctionTable::with_core_functions())
      : PlcFixture(std::move(functions)) {
    plc.locked([](ScanEngine& e, Memory&) {
      e.set_engine(GetParam());
      return 0;
    });
  }
};

}  // namespace plc_cell

#define PLC_CELL_ON_BOTH_ENGINES(Suite)                                                       \
  INSTANTIATE_TEST_SUITE_P(, Suite,                                                           \
                           ::testing::Values(::plc_cell::EngineChoice::Native,                \
                                             ::plc_cell::EngineChoice::Interpreter),          \
                           [](const ::testing::TestParamInfo<::plc_cell::EngineChoice>& i) {  \
                             return std::string(::plc_cell::engine_choice_name(i.param));     \
                           })
