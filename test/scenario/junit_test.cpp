// JUnit XML stays well-formed whatever a run reports: case names, file names, failure
// messages and details of random bytes are written, and an XML parser (python's
// xml.etree) reads every file back with the names it can hold unchanged.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "../core/run_tool.h"
#include "plc_cell/core/utf8.h"
#include "plc_cell/scenario/junit.h"

using namespace plc_cell;
using namespace plc_cell::scenario;

namespace {

// Bytes a report may carry: random bytes, XML's own delimiters, control characters,
// UTF-8 of every length, surrogates and sequences cut short.
std::string hostile(std::mt19937& rng) {
  static const char* const pieces[] = {"<", ">", "&", "\"", "'", "]]>", "&amp;", "\r", "\n", "\t", "\x01", "\x1B",
                                       "\x7F", "\xC3\xA9", "\xE2\x82\xAC", "\xF0\x9F\x99\x82", "\xED\xA0\x80",
                                       "\xEF\xBF\xBE", "\xC0\x80", "\xE2\x82", "\xFF", "\x80", "a", " "};
  std::string s;
  const int n = std::uniform_int_distribution<int>(0, 40)(rng);
  for (int i = 0; i < n; ++i) {
    if (rng() % 2) s += static_cast<char>(rng() & 0xFF);
    else s += pieces[rng() % (sizeof pieces / sizeof *pieces)];
  }
  return s;
}

}  // namespace

TEST(JUnit, HostileStringsStayWellFormed) {
  const std::string dir = ::testing::TempDir() + "/junit_hostile";
  ASSERT_EQ(plc_cell::testing::run_shell("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").status, 0);
  std::mt19937 rng(25);
  const int kFiles = 200;
  std::ostringstream names;  // the plain names, which must come back unchanged
  for (int f = 0; f < kFiles; ++f) {
    std::vector<CaseResult> results;
    for (int i = 0; i < 3; ++i) {
      CaseResult r;
      r.name = hostile(rng);
      r.file = (i == 2 ? "plain/" : "") + hostile(rng) + ".yaml";
      r.line = i;
      r.passed = i == 1;
      r.failure = hostile(rng);
      r.details = hostile(rng);
      results.push_back(r);
    }
    results[0].name = "plain <&\"> 'name' " + std::to_string(f);
    names << results[0].name << "\n";
    std::ofstream out(dir + "/" + std::to_string(f) + ".xml", std::ios::binary);
    write_junit(results, out);
  }
  std::ofstream(dir + "/names.txt") << names.str();
  // Every file parses, and each keeps its plain name.
  const char* check =
      "import sys, glob, xml.etree.ElementTree as E\n"
      "d = sys.argv[1]\n"
      "want = open(d + '/names.txt', encoding='utf-8').read().split('\\n')\n"
      "for i in range(int(sys.argv[2])):\n"
      "    root = E.parse('%s/%d.xml' % (d, i)).getroot()\n"
      "    got = [c.get('name') for c in root.iter('testcase')]\n"
      "    assert len(got) == 3 and got[0] == want[i], (i, got)\n"
      "    assert len(list(root.iter('failure'))) == 2, i\n"
      "print('parsed', sys.argv[2])\n";
  std::ofstream(dir + "/check.py") << check;
  const auto r = plc_cell::testing::run_shell("/usr/bin/python3 '" + dir + "/check.py' '" + dir + "' " +
                                              std::to_string(kFiles));
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("parsed 200"), std::string::npos) << r.out;
}

// What cannot be written as it is is shown so that a reader still sees which byte or
// character it was; line breaks and tabs survive in attributes.
TEST(JUnit, BytesXmlCannotHoldAreShownAsEscapes) {
  CaseResult r;
  r.name = "caf\xE9\x01 \xC3\xA9";
  r.file = "s.yaml";
  r.failure = "a\tb\nc\r";
  r.details = "<d>\x1B";
  std::ostringstream out;
  write_junit({r}, out);
  const std::string x = out.str();
  EXPECT_NE(x.find("name=\"caf\\xE9\\u0001 \xC3\xA9\""), std::string::npos) << x;
  EXPECT_NE(x.find("message=\"a&#9;b&#10;c&#13;\">a\tb\nc&#13;\n&lt;d&gt;\\u001B</failure>"), std::string::npos) << x;
  size_t i = 0;
  while (i < x.size()) ASSERT_NE(utf8::next(x, &i), utf8::kInvalid) << x;
}

TEST(JUnit, ARunOnATargetNamesItInEverySuiteAndListsItsProperties) {
  CaseResult r;
  r.name = "a";
  r.file = "dir/c.scenario.yaml";
  r.line = 3;
  r.passed = true;
  r.virtual_us = 1500000;
  JUnitRun run;
  run.target = "fatek://10.0.0.5:500";
  run.properties = {{"resolution", "3.1 ms: a poll every 2 ms"}, {"left as found", "yes"}};
  std::ostringstream out;
  write_junit({r}, out, run);
  const std::string x = out.str();
  EXPECT_NE(x.find("<testsuites name=\"plc_cell test --target fatek://10.0.0.5:500\""), std::string::npos) << x;
  EXPECT_NE(x.find("<testsuite name=\"c.scenario on fatek://10.0.0.5:500\""), std::string::npos) << x;
  EXPECT_NE(x.find("<testcase classname=\"c.scenario on fatek://10.0.0.5:500\" name=\"a\""), std::string::npos) << x;
  EXPECT_NE(x.find("<property name=\"resolution\" value=\"3.1 ms: a poll every 2 ms\"/>"), std::string::npos) << x;
  std::ostringstream plain;
  write_junit({r}, plain);
  EXPECT_EQ(plain.str().find("<properties>"), std::string::npos);
  EXPECT_NE(plain.str().find("<testsuite name=\"c.scenario\""), std::string::npos);
}
