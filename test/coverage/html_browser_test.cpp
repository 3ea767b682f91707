// The HTML page as a browser renders it. chromium-headless-shell opens a copy of index.html
// with a probe script appended (the page itself has no script) that writes the computed
// background of every network and measured line into the DOM; --dump-dom prints that DOM.
// So the colours asserted here are the ones the browser worked out from the page's CSS.
#include <fstream>
#include <map>
#include <regex>

#include "../core/run_tool.h"
#include "coverage_fixture.h"

namespace plc_cell {
namespace coverage {
namespace {

class HtmlInBrowser : public CoverageTest {
 protected:
  // dir/html/index.html with probe appended, as chromium-headless-shell renders it: the DOM
  // after the probe ran. "" (and a failure) if the browser did not run the page.
  std::string rendered(const char* probe, const std::string& options = "") {
    std::string page = read_all(dir + "/html/index.html");
    const size_t body_end = page.rfind("</body>");
    if (body_end == std::string::npos) {
      ADD_FAILURE() << "no </body> in the page";
      return "";
    }
    page.insert(body_end, probe);
    std::ofstream(dir + "/html/probe.html") << page;
    const testing::ToolResult chromium = testing::run_shell(
        "chromium-headless-shell --headless --no-sandbox --disable-gpu " + options + " --user-data-dir=" + dir +
            "/profile --dump-dom file://" + dir + "/html/probe.html 2>" + dir + "/chromium.log",
        120);
    EXPECT_EQ(chromium.status, 0);
    if (chromium.out.find("data-probed=\"yes\"") != std::string::npos) return chromium.out;
    ADD_FAILURE() << "chromium-headless-shell did not run the page (is it installed?); its log:\n"
                  << read_all(dir + "/chromium.log") << "\nits output:\n" << chromium.out;
    return "";
  }
};

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

  const std::string dom = rendered(kProbe);
  ASSERT_FALSE(dom.empty());

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
  // changed, and decided its network alone (MC/DC); of OUT Y0-Y2 only Y0 switched; JMP enabled.
  EXPECT_NE(dom.find("<td>1</td><td>3/4</td><td>2/4</td><td>1/3</td><td>1/3</td><td>1/3</td><td>1/1</td>"), std::string::npos);
  EXPECT_NE(dom.find("network 4 (line 8): not evaluated"), std::string::npos);
  EXPECT_EQ(dom.find("M1925 always ON"), std::string::npos);
}

// At 900 px (a laptop's half screen) the page fits: no line, column or heading runs off
// it, a long IL comment wraps and is shown whole (nothing clipped), and the cell's signal
// names stand beside the addresses.
const char* const kLayoutProbe =
    "<script>\n"
    "const view = document.documentElement.clientWidth;\n"
    "const out = [];\n"
    "for (const el of document.querySelectorAll('body *')) {\n"
    "  const r = el.getBoundingClientRect();\n"
    "  if (r.width && r.right > view + 0.5) out.push('off:' + el.tagName + '.' + el.className);\n"
    "  if (el.matches('.line span') && el.scrollWidth > el.clientWidth + 1)\n"
    "    out.push('clipped:' + el.className + '@' + el.parentElement.id);\n"
    "}\n"
    "const c = document.querySelector('#p1-l2 .comment');\n"
    "const lh = document.querySelector('#p1-l2 .no').getBoundingClientRect().height;  // one line\n"
    "document.body.setAttribute('data-view', view);\n"
    "document.body.setAttribute('data-page', document.documentElement.scrollWidth);\n"
    "document.body.setAttribute('data-problems', out.join(' ') || 'none');\n"
    "document.body.setAttribute('data-comment-lines', Math.round(c.getBoundingClientRect().height / lh));\n"
    "document.body.setAttribute('data-probed', 'yes');\n"
    "</script>\n";

TEST_F(HtmlInBrowser, At900PixelsLongCommentsWrapAndNothingRunsOffThePage) {
  std::string comment = "; the stop push button, normally closed: a wire break stops the belt as a press does";
  for (int i = 0; i < 4; ++i) comment += ", and so on, and so on, as long as a comment can be";
  const std::string path = write("a_rather_long_program_file_name_of_a_conveyor_cell_with_a_stop_button.il",
                                 "; stop button demo\n"
                                 "ORG X1        " + comment + "\n"
                                 "OUT Y0        ; conveyor\n"
                                 "END\n");
  Recorder rec;
  run_case(rec, path, {{{1, true}}}, {{"stop_pb", parse_address("X1")}, {"conveyor_run", parse_address("Y0")}});
  write_html({report(rec)}, dir + "/html");

  const std::string page = read_all(dir + "/html/index.html");
  EXPECT_NE(page.find("never changed: stop_pb (X1) always ON"), std::string::npos) << page;
  EXPECT_NE(page.find("coil OUT conveyor_run (Y0) never switched (rung always ON)"), std::string::npos) << page;
  const std::string dom = rendered(kLayoutProbe, "--window-size=900,800");
  ASSERT_FALSE(dom.empty());
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("data-view=\"(\\d+)\" data-page=\"(\\d+)\"")));
  EXPECT_GE(std::stoi(m[1]), 860);  // the window less a scroll bar at most
  EXPECT_LE(std::stoi(m[1]), 900);
  EXPECT_EQ(m[2], m[1]) << "the page is wider than the window";
  EXPECT_NE(dom.find("data-problems=\"none\""), std::string::npos) << dom.substr(dom.find("data-problems"), 600);
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("data-comment-lines=\"(\\d+)\"")));
  EXPECT_GE(std::stoi(m[1]), 3) << "the long comment does not wrap";
}

}  // namespace
}  // namespace coverage
}  // namespace plc_cell
