// Each libFuzzer target (test/fuzz/) runs a bounded number of inputs from its seed corpus:
// exit 0 = no crash, leak, sanitizer report or timeout. `make fuzz` runs them for longer.
// The IL parser, the cell YAML and the whole cell start from every example (examples/**)
// and every refused cell of the rejected corpus besides their own seeds, gathered when the
// test runs, so a new example or refused cell seeds them without being copied.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../../harness/child_process.h"

namespace {

constexpr int kLimitS = 900;  // one target's bounded run, with room for a loaded machine

namespace fs = std::filesystem;

std::string source(const std::string& rel) { return std::string(PLC_CELL_SOURCE_DIR) + "/" + rel; }

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The files under source folder `rel` (recursively) whose names end in `ext`, sorted.
std::vector<fs::path> files_under(const std::string& rel, const std::string& ext) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(source(rel)))
    if (e.is_regular_file() && e.path().string().size() > ext.size() &&
        e.path().string().compare(e.path().string().size() - ext.size(), ext.size(), ext) == 0)
      out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// A scratch folder of seeds, removed with the object.
class Seeds {
 public:
  Seeds() {
    const char* t = std::getenv("TMPDIR");
    dir_ = std::string(t && *t ? t : "/tmp") + "/plc_cell_seeds_XXXXXX";
    if (!::mkdtemp(&dir_[0])) dir_.clear();
  }
  ~Seeds() {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  void add(const std::string& name, const std::string& bytes) {
    std::ofstream(dir_ + "/" + std::to_string(count_++) + "_" + name, std::ios::binary) << bytes;
  }
  void add_files(const std::vector<fs::path>& files) {
    for (const auto& f : files) add(f.filename().string(), slurp(f));
  }
  const std::string& dir() const { return dir_; }
  int count() const { return count_; }

 private:
  std::string dir_;
  int count_ = 0;
};

// The IL of every example and refused program.
void il_seeds(Seeds& s) {
  s.add_files(files_under("examples", ".il"));
  s.add_files(files_under("test/fuzz/corpus/rejected", ".il"));
}

// The YAML of every example (cells and scenarios) and every refused cell.
void yaml_seeds(Seeds& s) {
  s.add_files(files_under("examples", ".yaml"));
  s.add_files(files_under("test/fuzz/corpus/rejected", ".yaml"));
}

// Every cell of examples/ and of the rejected corpus as the whole-cell target reads a cell
// as text: "<yaml>\n%%IL%%\n<il>\n%%RUN%%\n" (test/fuzz/cell_fuzz.cpp), the IL being the file
// its `program:` names. A leading comment makes the first byte odd: the text path.
void cell_seeds(Seeds& s) {
  static const std::regex program(R"(program:\s*([^\s,}]+))");
  for (const std::string folder : {"examples", "test/fuzz/corpus/rejected"})
    for (const auto& yaml : files_under(folder, ".yaml")) {
      const std::string text = slurp(yaml);
      std::smatch m;
      if (!std::regex_search(text, m, program)) continue;  // a scenario or bridge file, not a cell
      const fs::path il = yaml.parent_path() / m[1].str();
      if (!fs::exists(il)) continue;
      s.add(yaml.stem().string(), "# " + yaml.filename().string() + "\n" + text + "\n%%IL%%\n" + slurp(il) +
                                      "\n%%RUN%%\n");
    }
}

struct Run {
  int status;
  std::string out;
};

// New inputs go to a scratch folder (the first corpus argument), never into the source tree.
Run fuzz(const std::string& target, const std::string& corpus, int runs, int max_len = 512,
         const std::string& more_seeds = "") {
  const char* t = std::getenv("TMPDIR");
  std::string tmp = std::string(t && *t ? t : "/tmp") + "/plc_cell_fuzz_XXXXXX";
  if (!::mkdtemp(&tmp[0])) return {-1, "mkdtemp"};
  const std::string bin = std::string(PLC_CELL_FUZZ_DIR) + "/fuzz_" + target;
  const std::string seeds = std::string(PLC_CELL_SOURCE_DIR) + "/test/fuzz/corpus/" + corpus;
  const std::string cmd = bin + " -runs=" + std::to_string(runs) + " -seed=1 -max_len=" + std::to_string(max_len) + " -timeout=20 -rss_limit_mb=1024" +
                          " -artifact_prefix=" + tmp + "/ " + tmp + " " + seeds + " " + more_seeds + " 2>&1";
  // A bounded run: a fuzzer that hangs fails here, killed after kLimitS.
  const auto done = plc_cell::testing::run_shell(cmd, kLimitS);
  Run r{done.status, done.out};
  (void)std::system(("rm -rf '" + tmp + "'").c_str());
  if (r.out.size() > 6000) r.out = "..." + r.out.substr(r.out.size() - 6000);
  return r;
}

void expect_clean(const std::string& target, const std::string& corpus, int runs, int max_len = 512,
                  const std::string& more_seeds = "") {
  const Run r = fuzz(target, corpus, runs, max_len, more_seeds);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("Done " + std::to_string(runs) + " runs"), std::string::npos) << r.out;
}

}  // namespace

TEST(Fuzz, FatekDecoderAndSlave) { expect_clean("fatek_decoder", "fatek", 100000); }
TEST(Fuzz, IlParser) {
  Seeds s;
  il_seeds(s);
  ASSERT_GE(s.count(), 17);  // the example programs are there
  expect_clean("il_parser", "il", 10000, 4096, s.dir());
}
// Random valid programs on the native engine and the interpreter in lockstep, up to 200
// scans each with random inputs, forcing and interrupts (test/fuzz/native_lockstep_fuzz.cpp).
TEST(Fuzz, NativeEngineEqualsTheInterpreter) { expect_clean("native_lockstep", "native_lockstep", 3000, 4096); }
TEST(Fuzz, AddressParser) { expect_clean("address", "address", 50000); }
// The target also requires every error to name fuzz.yaml and a line (test/fuzz/config_fuzz.cpp).
TEST(Fuzz, CellConfigLoader) {
  Seeds s;
  yaml_seeds(s);
  ASSERT_GE(s.count(), 30);
  expect_clean("config", "config", 10000, 4096, s.dir());
}
TEST(Fuzz, MotionTableParserAndDecoder) { expect_clean("motion_table", "motion", 20000); }

// The servers' request handlers on a live Plc whose real-time loop scans (test/fuzz/live_plc.h):
// besides crashes and sanitizer reports, a scan longer than 100 ms or any fault is a finding.
// The _tsan builds run the same targets under ThreadSanitizer (handler thread vs scan thread).
TEST(Fuzz, ModbusHandlerOnLivePlc) { expect_clean("modbus_handler", "modbus", 3000); }
TEST(Fuzz, FatekSlaveOnLivePlc) { expect_clean("fatek_slave_live", "fatek", 50000); }
TEST(Fuzz, ModbusHandlerOnLivePlcThreadSanitizer) { expect_clean("modbus_handler_tsan", "modbus", 1000); }
TEST(Fuzz, FatekSlaveOnLivePlcThreadSanitizer) { expect_clean("fatek_slave_live_tsan", "fatek", 10000); }
TEST(Fuzz, TriSlaveOnLivePlc) { expect_clean("tri_slave_live", "tri", 50000); }
TEST(Fuzz, TriSlaveOnLivePlcThreadSanitizer) { expect_clean("tri_slave_live_tsan", "tri", 10000); }

// A TRi master's codec: any request body and any reply to it (test/fuzz/tri_codec_fuzz.cpp).
TEST(Fuzz, TriRequestAndResponseCodec) { expect_clean("tri_codec", "tri_codec", 100000); }

// Whole cells (YAML + IL + run bytes): the seeds are test/fuzz/corpus/cell/ (generated
// cells, regressions) and every cell of examples/ and of the rejected corpus, up to 8 KiB each.
// Generated and mutated whole cells (test/fuzz/cell_fuzz.cpp): about 20 executions a second under ASan.
TEST(Fuzz, WholeCell) {
  Seeds s;
  cell_seeds(s);
  ASSERT_GE(s.count(), 25);
  expect_clean("cell", "cell", 1000, 8192, s.dir());
}
