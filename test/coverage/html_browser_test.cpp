// The HTML page as a browser renders it. chromium-headless-shell opens a copy of index.html
// with a probe script appended (the page itself has no script) that writes the computed
// background of every network and measured line into the DOM; --dump-dom prints that DOM.
// So the colours asserted here are the ones the browser worked out from the page's CSS.
#include <map>
#include <regex>

#include "../core/run_tool.h"
#include "coverage_fixture.h"

namespace plc_cell {
namespace coverage {
namespace {

using HtmlInBrowser = CoverageTest;

const char* const kProbe =
    "<script>\n"
    "for (const el of document.querySelectorAll('.net, .listing .line'))\n"
    "  el.setAttribute('data-bg', getComputedStyle(el).backgroundColor);\n"
    "document.body.setAttribute('data-probed', 'yes');\n"
    "</script>\n";

TEST_F(HtmlInBrowser, NetworksAndLinesAreColouredByCoverage) {
  const std::string path = write("conveyor.il",
                                 "; conveyor: coverage demo\n"
                                 "ORG X0        ; start button\n"
                                 "OUT Y0        ; conveyor\n"
                                 "ORG X1        ; never pressed\n"
                                 "OUT Y1\n"
                                 "ORG M1925\n"
                                 "JMP SKIP\n"
                                 "ORG X2\n"
                                 "OUT Y2        ; jumped over\n"
                                 "LBL SKIP\n"
                                 "END\n");
  Recorder rec;
  run_case(rec, path, {{{0, true}}, {{0, false}}});
  write_html({report(rec)}, dir + "/html");

  std::string page = read_all(dir + "/html/index.html");
  const size_t body_end = page.rfind("</body>");
  ASSERT_NE(body_end, std::string::npos);
  page.insert(body_end, kProbe);
  std::ofstream(dir + "/html/probe.html") << page;

  const testing::ToolResult chromium = testing::run_shell(
      "chromium-headless-shell --headless --no-sandbox --disable-gpu --user-data-dir=" + dir +
          "/profile --dump-dom file://" + dir + "/html/probe.html 2>" + dir + "/chromium.log",
      120);
  const std::string& dom = chromium.out;
  EXPECT_EQ(chromium.status, 0);
  ASSERT_NE(dom.find("data-probed=\"yes\""), std::string::npos)
      << "chromium-headless-shell did not run the page (is it installed?); its log:\n"
      << read_all(dir + "/chromium.log") << "\nits output:\n" << dom;

  // Green: energised. Red: evaluated, never energised. Grey: not evaluated.
  std::map<std::string, std::string> nets;
  const std::regex net("<div class=\"net (\\w+)\" data-network=\"(\\d+)\" data-bg=\"([^\"]*)\">");
  for (std::sregex_iterator m(dom.begin(), dom.end(), net), end; m != end; ++m)
    nets[(*m)[2]] = (*m)[1].str() + " " + (*m)[3].str();
  EXPECT_EQ(nets, (std::map<std::string, std::string>{{"1", "ok rgb(232, 247, 232)"},
                                                       {"2", "bad rgb(251, 227, 227)"},
                                                       {"3", "ok rgb(232, 247, 232)"},
                                                       {"4", "off rgb(239, 239, 239)"}}));

  // Each measured line in its own colour; unmeasured lines (LBL, END, the comment) have none.
  std::map<int, std::string> lines;
  const std::regex line("<div class=\"line ?(\\w*)\" id=\"p1-l(\\d+)\" data-bg=\"([^\"]*)\">");
  for (std::sregex_iterator m(dom.begin(), dom.end(), line), end; m != end; ++m)
    lines[std::stoi((*m)[2])] = (*m)[1].str() + " " + (*m)[3].str();
  const std::string ok = "ok rgb(185, 232, 185)", bad = "bad rgb(245, 181, 181)", off = "off rgb(214, 214, 214)";
  const std::string none = " rgba(0, 0, 0, 0)";
  // ORG M1925 is not measured: M1925 is always ON, the contact cannot change.
  EXPECT_EQ(lines, (std::map<int, std::string>{{1, none}, {2, ok}, {3, ok}, {4, bad}, {5, bad}, {6, none},
                                               {7, ok}, {8, off}, {9, off}, {10, none}, {11, none}}));

  // Summary: 1 run; networks 1-3 evaluated, 1 and 3 energised; of X0, X1, X2 only X0
  // changed; of OUT Y0-Y2 only Y0 switched; JMP enabled.
  EXPECT_NE(dom.find("<td>1</td><td>3/4</td><td>2/4</td><td>1/3</td><td>1/3</td><td>1/1</td>"), std::string::npos);
  EXPECT_NE(dom.find("network 4: not evaluated"), std::string::npos);
  EXPECT_EQ(dom.find("M1925 always ON"), std::string::npos);
}

}  // namespace
}  // namespace coverage
}  // namespace plc_cell
