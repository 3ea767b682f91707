// The text, JSON and HTML renderings, byte for byte, of one case over kTwoNetworks (the
// values are those of recorder_test's first test, worked out there).
#include <sstream>

#include "plc_cell/core/error.h"
#include "coverage_fixture.h"

namespace plc_cell {
namespace coverage {
namespace {

class Outputs : public CoverageTest {
 protected:
  void SetUp() override {
    CoverageTest::SetUp();
    path = write("two.il", kTwoNetworks);
    run_case(rec, path, {{{0, true}}, {{0, false}}});
  }
  std::string path;
  Recorder rec;
};

TEST_F(Outputs, Text) {
  std::ostringstream out;
  write_text({report(rec)}, out);
  EXPECT_EQ(out.str(),
            "coverage of " + path + " (1 run)\n"
            "  networks evaluated 2/2, energised 1/2\n"
            "  contacts changed 1/3, coils switched 1/2, FUNs enabled 0/0\n"
            "  contacts with MC/DC (unique cause) 1/3\n" +
            path + ":3 contact X1 never changed (always OFF)\n" +
            path + ":5 network 2 never energised\n" +
            path + ":5 contact X2 never changed (always OFF)\n" +
            path + ":6 coil OUT Y1 never switched (rung always OFF)\n");
}

// The cell's signal names beside the addresses: findings, and JSON's "signal" (its
// "name" stays the instruction's, as before).
TEST_F(Outputs, SignalNamesStandBesideTheAddresses) {
  Recorder named;
  run_case(named, path, {{{0, true}}, {{0, false}}},
           {{"stop_pb", parse_address("X1")}, {"belt", parse_address("Y1")}, {"spare", parse_address("X9")}});
  std::ostringstream text;
  write_text({report(named)}, text);
  EXPECT_NE(text.str().find(path + ":3 contact stop_pb (X1) never changed (always OFF)\n"), std::string::npos)
      << text.str();
  EXPECT_NE(text.str().find(path + ":5 contact X2 never changed (always OFF)\n"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find(path + ":6 coil OUT belt (Y1) never switched (rung always OFF)\n"), std::string::npos)
      << text.str();
  std::ostringstream json;
  write_json({report(named)}, json);
  EXPECT_NE(json.str().find("{\"kind\": \"contact\", \"line\": 3, \"name\": \"X1\", \"signal\": \"stop_pb\", "
                            "\"seen\": [\"off\"]"),
            std::string::npos)
      << json.str();
  EXPECT_NE(json.str().find("{\"kind\": \"contact\", \"line\": 2, \"name\": \"X0\", \"seen\""), std::string::npos)
      << json.str();
  EXPECT_NE(json.str().find("\"message\": \"coil OUT belt (Y1) never switched (rung always OFF)\""), std::string::npos)
      << json.str();
}

TEST_F(Outputs, TextOfSeveralPrograms) {
  const std::string other = write("all.il", "ORG X0\nOUT Y0\nEND\n");
  Recorder all;
  run_case(all, other, {{{0, true}}, {{0, false}}});
  std::ostringstream out;
  write_text({report(all), report(all)}, out);
  const std::string one = "coverage of " + other + " (1 run)\n"
                          "  networks evaluated 1/1, energised 1/1\n"
                          "  contacts changed 1/1, coils switched 1/1, FUNs enabled 0/0\n"
                          "  contacts with MC/DC (unique cause) 1/1\n"
                          "  every network, contact, coil and FUN exercised\n";
  EXPECT_EQ(out.str(), one + "\n" + one);
}

TEST_F(Outputs, Json) {
  std::ostringstream out;
  write_json({report(rec)}, out);
  EXPECT_EQ(out.str(),
            "{\n"
            "  \"format\": \"plc_cell coverage\",\n"
            "  \"version\": 1,\n"
            "  \"programs\": [\n"
            "    {\n"
            "      \"file\": \"" + path + "\",\n"
            "      \"runs\": 1,\n"
            "      \"totals\": {\"networks\": 2, \"networks_evaluated\": 2, \"networks_energised\": 1, "
            "\"contacts\": 3, \"contacts_changed\": 1, \"contacts_mcdc\": 1, \"coils\": 2, \"coils_switched\": 1, \"funs\": 0, "
            "\"funs_enabled\": 0},\n"
            "      \"networks\": [\n"
            "        {\"number\": 1, \"line\": 2, \"end_line\": 4, \"routine\": \"\", \"evaluated\": true, "
            "\"energised\": true,\n"
            "         \"items\": [\n"
            "           {\"kind\": \"contact\", \"line\": 2, \"name\": \"X0\", \"seen\": [\"off\", \"on\"], "
            "\"exercised\": true, \"mcdc\": true},\n"
            "           {\"kind\": \"contact\", \"line\": 3, \"name\": \"X1\", \"seen\": [\"off\"], "
            "\"exercised\": false, \"mcdc\": false},\n"
            "           {\"kind\": \"coil\", \"line\": 4, \"name\": \"OUT Y0\", \"seen\": [\"off\", \"on\"], "
            "\"exercised\": true}\n"
            "         ]},\n"
            "        {\"number\": 2, \"line\": 5, \"end_line\": 6, \"routine\": \"\", \"evaluated\": true, "
            "\"energised\": false,\n"
            "         \"items\": [\n"
            "           {\"kind\": \"contact\", \"line\": 5, \"name\": \"X2\", \"seen\": [\"off\"], "
            "\"exercised\": false, \"mcdc\": false},\n"
            "           {\"kind\": \"coil\", \"line\": 6, \"name\": \"OUT Y1\", \"seen\": [\"off\"], "
            "\"exercised\": false}\n"
            "         ]}\n"
            "      ],\n"
            "      \"findings\": [\n"
            "        {\"line\": 3, \"message\": \"contact X1 never changed (always OFF)\"},\n"
            "        {\"line\": 5, \"message\": \"network 2 never energised\"},\n"
            "        {\"line\": 5, \"message\": \"contact X2 never changed (always OFF)\"},\n"
            "        {\"line\": 6, \"message\": \"coil OUT Y1 never switched (rung always OFF)\"}\n"
            "      ]\n"
            "    }\n"
            "  ]\n"
            "}\n");
}

TEST_F(Outputs, JsonOfNothing) {
  std::ostringstream out;
  write_json({}, out);
  EXPECT_EQ(out.str(), "{\n  \"format\": \"plc_cell coverage\",\n  \"version\": 1,\n  \"programs\": []\n}\n");
}

TEST_F(Outputs, HtmlIsTheSameBytesEveryTime) {
  write_html({report(rec)}, dir + "/a/b");
  write_html({report(rec)}, dir + "/c");
  const std::string page = read_all(dir + "/a/b/index.html");
  EXPECT_EQ(page, read_all(dir + "/c/index.html"));
  EXPECT_EQ(page.find("http"), std::string::npos) << "the page must fetch nothing";
  EXPECT_NE(page.find("<span class=\"code\">ORG X2      </span><span class=\"comment\">; never pressed</span>"),
            std::string::npos);
}

TEST_F(Outputs, HtmlIntoAFileFails) {
  write("plain", "x");
  try {
    write_html({report(rec)}, dir + "/plain/sub");
    FAIL() << "wrote below a file";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("coverage: cannot create " + dir + "/plain/sub: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace coverage
}  // namespace plc_cell
