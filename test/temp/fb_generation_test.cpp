// The per-cell generation switch (modules.generation): which FUN86 and FUN72/73/85 a
// program gets, the checker's error for an FB instruction in an FBs cell, and the YAML
// errors for modules of the other generation.
#include <gtest/gtest.h>

#include "config_error.h"
#include "fb_cell.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/temp/fb_modules.h"

namespace plc_cell {
namespace temp {
namespace {

std::string parse_error(Generation g, const std::string& program) {
  try {
    parse_program(program, "p.il", fb_table(g));
  } catch (const SourceError& e) {
    return e.what();
  }
  return "no error";
}

TEST(FbGeneration, Fun72To85RejectedInAnFbsCell) {
  const std::string e72 = parse_error(Generation::FBs, "ORG M0\nFUN 72 Tp=0 Pl=0 Sm=0 Ym=Y16 AR=R3842 TR=R0 WR=R100\nEND\n");
  EXPECT_NE(e72.find("p.il:2:5"), std::string::npos) << e72;
  EXPECT_NE(e72.find("FUN 72 TP4: belongs to the FB generation"), std::string::npos) << e72;
  EXPECT_NE(e72.find("modules.generation: FB"), std::string::npos) << e72;
  const std::string e73 = parse_error(Generation::FBs, "ORG M0\nLD M1\nTSTC Tp=0\nEND\n");  // by mnemonic
  EXPECT_NE(e73.find("p.il:3:1"), std::string::npos) << e73;
  EXPECT_NE(e73.find("FUN 73 TSTC: belongs to the FB generation"), std::string::npos) << e73;
  const std::string e85 = parse_error(Generation::FBs, "ORG M0\nFUN 85 Tp=0 Pl=0 Zn=24 Yn=Y16 SR=R0 WR=R100\nEND\n");
  EXPECT_NE(e85.find("FUN 85 TPSNS: belongs to the FB generation"), std::string::npos) << e85;
  // An unknown number keeps the plain message.
  EXPECT_NE(parse_error(Generation::FBs, "ORG M0\nFUN 999\nEND\n").find("is not available"), std::string::npos);
}

TEST(FbGeneration, EachGenerationHasItsOwnFun86) {
  const char* fbs86 = "ORG M0\nLD M1\nFUN 86 Md=0 Yn=Y0 Sn=0 Zn=1 Sv=R100 Os=R110 PR=R120 IR=R130 DR=R140 OR=R200 WR=R300\nEND\n";
  const char* fb86 = "ORG M0\nLD M1\nFUN 86 Yn=Y0 Sn=0 Zn=1 Sv=R100 Os=R110 PR=R120 IR=R130 DR=R140 OR=R200 WR=R300\nEND\n";
  EXPECT_EQ(parse_error(Generation::FBs, fbs86), "no error");
  EXPECT_EQ(parse_error(Generation::FB, fb86), "no error");
  // The FB version has no Md; the FBs version needs it.
  EXPECT_NE(parse_error(Generation::FB, fbs86).find("has no operand 'Md'"), std::string::npos);
  EXPECT_NE(parse_error(Generation::FBs, fb86).find("needs operand"), std::string::npos);
  EXPECT_EQ(parse_error(Generation::FB, "ORG M0\nFUN 72 Tp=0 Pl=0 Sm=0 Ym=Y16 AR=R3842 TR=R0 WR=R100\nEND\n"), "no error");
}

TEST(FbGeneration, YamlOfTheOtherGenerationIsAnError) {
  EXPECT_NE(config_error("modules:\n  generation: FBS\n").find("c.yaml:2:15: error: key 'modules.generation': FBs or FB"),
            std::string::npos)
      << config_error("modules:\n  generation: FBS\n");
  const std::string fbs_modules = config_error(
      "modules:\n  generation: FB\n  temperature:\n    modules: [{type: 2TC}]\n");
  EXPECT_NE(fbs_modules.find("c.yaml:4:5: error: key 'modules.temperature': the FBs temperature modules belong to the FBs generation"),
            std::string::npos)
      << fbs_modules;
  const std::string fb_modules = config_error(
      "modules:\n  fb_temperature:\n    modules: [{type: 2AK4, outputs: Y16}]\n");
  EXPECT_NE(fb_modules.find("c.yaml:3:5: error: key 'modules.fb_temperature': the FB-series modules need modules.generation: FB"),
            std::string::npos)
      << fb_modules;
}

TEST(FbGeneration, FbModuleYamlErrors) {
  auto err = [](const std::string& mods) {
    return config_error("modules:\n  generation: FB\n  fb_temperature:\n    modules:\n" + mods);
  };
  EXPECT_NE(err("      - {type: 2AX4, outputs: Y16}\n").find("unknown module '2AX4'"), std::string::npos);
  EXPECT_NE(err("      - {type: 2AK4}\n").find("fb_temperature.modules[0].outputs': missing"), std::string::npos);
  EXPECT_NE(err("      - {type: 2AK4, outputs: R16}\n").find("expected Y0..Y248"), std::string::npos);
  EXPECT_NE(err("      - {type: 2AH4, outputs: Y0, polarity: unipolar}\n").find("bipolar only"), std::string::npos);
  EXPECT_NE(err("      - {type: 2AK4, outputs: Y0, span: 7}\n").find("5 or 10"), std::string::npos);
  EXPECT_NE(err("      - {type: 4AK24, outputs: Y0}\n      - {type: 2AK4, outputs: Y8}\n").find("must be installed alone"),
            std::string::npos);
  EXPECT_NE(err("      - {type: 2AK4, outputs: Y0, channels: [{plant: nowhere}]}\n").find("unknown plant 'nowhere'"),
            std::string::npos);
}

TEST(FbGeneration, ModulesTakeThreeAiEach) {
  // "the analog input address must be added 3" (B:360): temperature AIs R3842, R3845, R3848.
  const FbConfig c = parse_fb_config(
      YAML::Load("first_ai: 0\nmodules: [{type: 2AK4, outputs: Y16}, {type: 2AJ4, outputs: Y24}, {type: 2AH4, outputs: Y32}]"),
      "c.yaml");
  EXPECT_EQ(3840 + c.modules[0].temperature_ai(0), 3842u);
  EXPECT_EQ(3840 + c.modules[1].temperature_ai(0), 3845u);
  EXPECT_EQ(3840 + c.modules[2].temperature_ai(0), 3848u);
  const FbConfig big = parse_fb_config(YAML::Load("modules: [{type: 4AJ18, outputs: Y16}]"), "c.yaml");
  EXPECT_EQ(big.modules[0].points, 18);
  EXPECT_EQ(3840 + big.modules[0].temperature_ai(3), 3847u);  // the 8th AI
}

TEST(FbGeneration, FbDefaultsOnTheFirstScan) {
  FbCell c("modules:\n  generation: FB\n", "ORG M0\nINC R0\nEND\n");
  c.run_to(0);
  // B:385-B:436, B:705-B:711: R4005 0 (2 s / 2 s), R4008 350 degrees, R4014 500 ms ...
  EXPECT_EQ(c.r("R4005"), 0);
  EXPECT_EQ(c.r("R4007"), 600);
  EXPECT_EQ(c.r("R4008"), 350);
  EXPECT_EQ(c.r("R4014"), 500);
  EXPECT_EQ(c.r("R4016"), 248);
  EXPECT_EQ(c.r("R4019"), 280);
  EXPECT_EQ(c.r("R4020"), 1);
  EXPECT_EQ(c.r("R4021"), 8000);
  EXPECT_EQ(c.r("R4023"), 1024);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
