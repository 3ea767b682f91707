// Parse-time checks of the counter and interrupt instructions.
#include <gtest/gtest.h>

#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace {

std::string error_of(const std::string& il) {
  Plc plc{SoftCell::functions()};
  try {
    plc.load_program_text(il, "t.il");
  } catch (const SourceError& e) {
    return e.diagnostics().at(0).to_string();
  }
  return "";
}

TEST(HscFunctions, OperandsAreCheckedWhenTheProgramIsParsed) {
  EXPECT_EQ(error_of("ORG M1925\nFUN 92 HSCTR CN=4\nFUN 93 CN=3 D=1\nFUN 145 EN LBL=X3+I\n"
                     "FUN 146 DIS LBL=hst2i\nFUN 74 IMDIO D=Y8 N=8\nEND\n"),
            "");
  EXPECT_NE(error_of("ORG M1925\nFUN 92 CN=5\nEND\n").find("t.il:2:"), std::string::npos);
  EXPECT_NE(error_of("ORG M1925\nFUN 93 CN=0 D=2\nEND\n").find("D must be 0 (CV) or 1 (PV)"), std::string::npos);
  EXPECT_NE(error_of("ORG M1925\nFUN 145 EN LBL=LOOP\nEND\n").find("'LOOP' is not an interrupt label"),
            std::string::npos);
  EXPECT_NE(error_of("ORG M1925\nFUN 146 DIS LBL=1MSI\nEND\n").find("R4162"), std::string::npos);
  EXPECT_NE(error_of("ORG M1925\nFUN 74 IMDIO D=M0 N=1\nEND\n").find("input X or output Y"), std::string::npos);
  EXPECT_NE(error_of("ORG M1925\nFUN 74 IMDIO D=Y250 N=8\nEND\n").find("N must be"), std::string::npos);
}

}  // namespace
}  // namespace plc_cell
