// Each libFuzzer target (test/fuzz/) runs a bounded number of inputs from its seed corpus:
// exit 0 = no crash, leak, sanitizer report or timeout. `make fuzz` runs them for longer.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdlib>
#include <string>

namespace {

struct Run {
  int status;
  std::string out;
};

// New inputs go to a scratch folder (the first corpus argument), never into the source tree.
Run fuzz(const std::string& target, const std::string& corpus, int runs, int max_len = 512) {
  const char* t = std::getenv("TMPDIR");
  std::string tmp = std::string(t && *t ? t : "/tmp") + "/plc_cell_fuzz_XXXXXX";
  if (!::mkdtemp(&tmp[0])) return {-1, "mkdtemp"};
  const std::string bin = std::string(PLC_CELL_FUZZ_DIR) + "/fuzz_" + target;
  const std::string seeds = std::string(PLC_CELL_SOURCE_DIR) + "/test/fuzz/corpus/" + corpus;
  const std::string cmd = bin + " -runs=" + std::to_string(runs) + " -seed=1 -max_len=" + std::to_string(max_len) + " -timeout=20 -rss_limit_mb=1024" +
                          " -artifact_prefix=" + tmp + "/ " + tmp + " " + seeds + " 2>&1";
  Run r{-1, ""};
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
    const int st = ::pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  }
  (void)std::system(("rm -rf '" + tmp + "'").c_str());
  if (r.out.size() > 6000) r.out = "..." + r.out.substr(r.out.size() - 6000);
  return r;
}

void expect_clean(const std::string& target, const std::string& corpus, int runs, int max_len = 512) {
  const Run r = fuzz(target, corpus, runs, max_len);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("Done " + std::to_string(runs) + " runs"), std::string::npos) << r.out;
}

}  // namespace

TEST(Fuzz, FatekDecoderAndSlave) { expect_clean("fatek_decoder", "fatek", 100000); }
TEST(Fuzz, IlParser) { expect_clean("il_parser", "il", 5000); }
// Random valid programs on the native engine and the interpreter in lockstep, up to 200
// scans each with random inputs, forcing and interrupts (test/fuzz/native_lockstep_fuzz.cpp).
TEST(Fuzz, NativeEngineEqualsTheInterpreter) { expect_clean("native_lockstep", "native_lockstep", 3000, 4096); }
TEST(Fuzz, AddressParser) { expect_clean("address", "address", 50000); }
TEST(Fuzz, CellConfigLoader) { expect_clean("config", "config", 3000); }
TEST(Fuzz, MotionTableParserAndDecoder) { expect_clean("motion_table", "motion", 20000); }

// The servers' request handlers on a live Plc whose real-time loop scans (test/fuzz/live_plc.h):
// besides crashes and sanitizer reports, a scan longer than 50 ms or any fault is a finding.
// The _tsan builds run the same targets under ThreadSanitizer (handler thread vs scan thread).
TEST(Fuzz, ModbusHandlerOnLivePlc) { expect_clean("modbus_handler", "modbus", 3000); }
TEST(Fuzz, FatekSlaveOnLivePlc) { expect_clean("fatek_slave_live", "fatek", 50000); }
TEST(Fuzz, ModbusHandlerOnLivePlcThreadSanitizer) { expect_clean("modbus_handler_tsan", "modbus", 1000); }
TEST(Fuzz, FatekSlaveOnLivePlcThreadSanitizer) { expect_clean("fatek_slave_live_tsan", "fatek", 10000); }
TEST(Fuzz, TriSlaveOnLivePlc) { expect_clean("tri_slave_live", "tri", 50000); }
TEST(Fuzz, TriSlaveOnLivePlcThreadSanitizer) { expect_clean("tri_slave_live_tsan", "tri", 10000); }

// A TRi master's codec: any request body and any reply to it (test/fuzz/tri_codec_fuzz.cpp).
TEST(Fuzz, TriRequestAndResponseCodec) { expect_clean("tri_codec", "tri_codec", 100000); }

// Whole cells (YAML + IL + run bytes): the seeds are the examples/ cells, up to 4 KiB each.
// Generated and mutated whole cells (test/fuzz/cell_fuzz.cpp): about 20 executions a second under ASan.
TEST(Fuzz, WholeCell) { expect_clean("cell", "cell", 1000, 8192); }
