// The ladder JSON in the shape the monitor's page and server read (docs/ladder.md).
#include <nlohmann/json.hpp>

#include <set>

#include "ladder_fixture.h"
#include "plc_cell/ladder/json.h"

namespace plc_cell {
namespace ladder {
namespace test {

TEST(LadderJson, ANetworkHasTheContractFields) {
  const std::string il = "; the latch\nORG X0\nOR Y0\nOUT Y0\nEND\n";
  Layout l = lay(il, {{"start_pb", parse_address("X0")}, {"belt", parse_address("Y0")}});
  l.file = "latch.il";
  l.version = 3;
  const nlohmann::json j = to_json(l);
  EXPECT_EQ(j["file"], "latch.il");
  EXPECT_EQ(j["version"], 3);
  EXPECT_EQ(j["signals"]["X0"], "start_pb");
  EXPECT_EQ(j["signals"]["Y0"], "belt");
  const nlohmann::json& n = j["networks"][0];
  EXPECT_EQ(n["index"], 0);
  EXPECT_EQ(n["line"], 2);
  EXPECT_EQ(n["comment"], "the latch");
  EXPECT_EQ(n["drawable"], true);
  EXPECT_EQ(n["reason"], "");
  EXPECT_EQ(n["rows"], 2);
  EXPECT_EQ(n["cols"], 1);
  ASSERT_EQ(n["il"].size(), 3u);
  EXPECT_EQ(n["il"][0], (nlohmann::json{{"line", 2}, {"text", "ORG X0"}}));
  bool contact = false, coil = false;
  for (const auto& e : n["elements"]) {
    for (const char* key : {"id", "row", "col", "type", "line"}) EXPECT_TRUE(e.contains(key)) << key;
    if (e["address"] == "X0") {
      contact = true;
      EXPECT_EQ(e["type"], "contact");
      EXPECT_EQ(e["form"], "no");
      EXPECT_EQ(e["name"], "start_pb");
      EXPECT_EQ(e["line"], 2);
    }
    if (e["type"] == "coil") {
      coil = true;
      EXPECT_EQ(e["form"], "out");
      EXPECT_EQ(e["address"], "Y0");
      EXPECT_EQ(e["name"], "belt");
      EXPECT_EQ(e["col"], 1);
    }
  }
  EXPECT_TRUE(contact && coil);
  ASSERT_EQ(n["wires"].size(), 2u);
  for (const auto& w : n["wires"]) {
    EXPECT_EQ(w["v"], true);
    EXPECT_TRUE(w.contains("col") && w.contains("from") && w.contains("to") && w.contains("id"));
  }
}

TEST(LadderJson, ElementAndWireIdsShareOneSpace) {
  const Network n = net0("ORG X0\nAND X1\nOR X2\nLD X3\nOR X4\nANDLD\nOUT Y0\nOUT Y1\nEND\n");
  std::set<int> ids;
  for (const Element& e : n.elements) EXPECT_TRUE(ids.insert(e.id).second) << e.id;
  for (const Wire& w : n.wires) EXPECT_TRUE(ids.insert(w.id).second) << w.id;
  EXPECT_EQ(static_cast<int>(ids.size()), *ids.rbegin() + 1);  // 0..n-1
}

TEST(LadderJson, OutputsCarryTheirOwnFields) {
  const Network n = net0("ORG X0\nTMR T5 100\nADD Sa=D0 Sb=K1 D=D2\nJMP AHEAD\nLBL AHEAD\nEND\n");
  const nlohmann::json j = to_json(n);
  const nlohmann::json& timer = j["elements"][1];
  EXPECT_EQ(timer["type"], "timer");
  EXPECT_EQ(timer["address"], "T5");
  EXPECT_EQ(timer["preset"], "100");
  EXPECT_EQ(timer["values"], (nlohmann::json{"T5", "RT5"}));
  EXPECT_EQ(timer["col"], 1);
  const nlohmann::json& fun = j["elements"][2];
  EXPECT_EQ(fun["type"], "fun");
  EXPECT_EQ(fun["fun"], 11);
  EXPECT_EQ(fun["mnemonic"], "ADD");
  EXPECT_EQ(fun["pulse"], false);
  EXPECT_EQ(fun["d32"], false);
  EXPECT_EQ(fun["operands"][0], (nlohmann::json{{"name", "Sa"}, {"text", "D0"}, {"address", "D0"}}));
  EXPECT_EQ(fun["operands"][1], (nlohmann::json{{"name", "Sb"}, {"text", "K1"}}));
  EXPECT_EQ(fun["inputs"], (nlohmann::json::array({{{"name", "EN"}, {"row", 1}}})));
  const nlohmann::json& jump = j["elements"][3];
  EXPECT_EQ(jump["type"], "jump");
  EXPECT_EQ(jump["label"], "AHEAD");
  EXPECT_EQ(jump["row"], 2);
}

TEST(LadderJson, AnUndrawableNetworkKeepsItsIlAndReason) {
  const nlohmann::json j = to_json(net0("ORG X0\nOUT Y0\nOR X1\nOUT Y1\nEND\n"));
  EXPECT_EQ(j["drawable"], false);
  EXPECT_NE(j["reason"].get<std::string>().find("line 4"), std::string::npos);
  EXPECT_EQ(j["il"].size(), 4u);
  EXPECT_TRUE(j["elements"].empty());
  EXPECT_EQ(j["instructions"], (nlohmann::json{0, 4}));  // for the coverage of its IL lines
}

TEST(LadderJson, FlowIsTheNetworkAndItsEnergisedIds) {
  Flow f;
  f.net = 2;
  f.on = {0, 1, 10};
  EXPECT_EQ(to_json(f), (nlohmann::json{{"net", 2}, {"on", {0, 1, 10}}}));
}

}  // namespace test
}  // namespace ladder
}  // namespace plc_cell
