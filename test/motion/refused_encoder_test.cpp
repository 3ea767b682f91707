// A cell whose axis encoder would share a counter with another source is refused with a
// message, and the half-built cell is torn down cleanly. Found by the whole-cell fuzzer:
// the refused source stayed bound to its pins, so tearing the cell down threw again from
// a destructor and `plc_cell sim` died in std::terminate instead of reporting the error.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "plc_cell/core/error.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(RefusedEncoder, SharedCounterIsAnErrorNotACrash) {
  const std::string yaml = write("refused_encoder.yaml",
                                 "cell: {name: refused}\n"
                                 "counters:\n"
                                 "  hsc0: {mode: MD0, b: true}\n"
                                 "  hsc3: {mode: MD7}\n"  // A/B on X12/X13
                                 "  sources:\n"
                                 "    - {name: belt, type: pulses, a: X12, hz: 100}\n"
                                 "axes:\n"
                                 "  pso0: {output: UD, wiring: {Y0: X0, Y1: X1}}\n"  // attached before pso2
                                 "  pso2:\n"
                                 "    output: UD\n"
                                 "    encoder: {a: X13, b: X14}\n");  // line 11
  const std::string il = write("refused_encoder.il", "ORG M1925\nOUT M0\nEND\n");
  try {
    SoftCell cell(yaml, il);
    FAIL() << "a counter driven by two sources was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("refused_encoder.yaml:11:"), std::string::npos) << what;
    EXPECT_NE(what.find("HSC3: its counting inputs are driven by two sources (belt, pso2.encoder)"), std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace plc_cell
