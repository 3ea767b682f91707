#pragma once
// Programs written to a scratch folder (the report re-reads them) and PLCs in RUN that
// scan them on a virtual clock, several per test: coverage sums over fresh PLCs.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/coverage/recorder.h"

namespace plc_cell {
namespace coverage {

// Y0's network energised and switched; X1, X2 and Y1's network never exercised (one case
// scanned with X0 ON, then OFF).
inline const char* const kTwoNetworks =
    "; Y0 runs while X0 and not X1\n"
    "ORG X0\n"
    "AND NOT X1\n"
    "OUT Y0\n"
    "ORG X2      ; never pressed\n"
    "OUT Y1\n"
    "END\n";

class CoverageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/plc_cell_coverage_XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir = tmpl;
  }
  void TearDown() override { std::filesystem::remove_all(dir); }

  std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    return path;
  }
  std::unique_ptr<Plc> plc_running(const std::string& path) {
    auto plc = std::make_unique<Plc>();
    plc->load_program_file(path);
    EXPECT_TRUE(plc->set_mode(RunMode::Run));
    return plc;
  }
  using Inputs = std::vector<std::pair<uint32_t, bool>>;  // X number, level
  // One scan with the given inputs set (the rest keep their level), 10 ms after the last.
  void scan(Plc& plc, const Inputs& inputs = {}) {
    for (const auto& in : inputs) plc.set_input(in.first, in.second);
    plc.scan(now_us);
    now_us += 10000;
  }
  // One test case: a fresh PLC running path, recorded by rec, one scan per entry of scans.
  void run_case(Recorder& rec, const std::string& path, const std::vector<Inputs>& scans,
                const SignalNames& names = {}) {
    auto plc = plc_running(path);
    rec.attach(*plc, names);
    for (const Inputs& in : scans) scan(*plc, in);
    rec.detach(*plc);
  }
  static const Network& network(const Report& r, uint32_t number) { return r.networks.at(number - 1); }
  static const Item& item(const Report& r, int line) {
    for (const Network& n : r.networks)
      for (const Item& it : n.items)
        if (it.line == line) return it;
    throw std::runtime_error("no item on line " + std::to_string(line));
  }
  // The totals as the text summary words them, to compare in one line.
  static std::string totals(const Report& r) {
    const Totals& t = r.totals;
    auto of = [](uint32_t n, uint32_t m) { return std::to_string(n) + "/" + std::to_string(m); };
    return "networks evaluated " + of(t.networks_evaluated, t.networks) + ", energised " +
           of(t.networks_energised, t.networks) + ", contacts changed " + of(t.contacts_changed, t.contacts) +
           ", coils switched " + of(t.coils_switched, t.coils) + ", FUNs enabled " + of(t.funs_enabled, t.funs);
  }
  // "line: message", in report order.
  static std::vector<std::string> findings(const Report& r) {
    std::vector<std::string> out;
    for (const Finding& f : r.findings) out.push_back(std::to_string(f.line) + ": " + f.message);
    return out;
  }
  static std::string read_all(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static std::string seen(const Item& it) {
    return std::string(it.seen_off ? "off" : "") + (it.seen_off && it.seen_on ? "+" : "") + (it.seen_on ? "on" : "") +
           (it.evaluated() ? "" : "none");
  }

  std::string dir;
  uint64_t now_us = 0;
};

}  // namespace coverage
}  // namespace plc_cell
