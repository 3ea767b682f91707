// The command line fuzzed: argument vectors built from the tool's own grammar (commands,
// options, values of the right and wrong kinds) mixed with junk. Whatever the arguments,
// `plc_cell` exits by itself with 0, 1 or 2 (never by a signal, never hangs), and a
// refusal says why. The seed is fixed, so a failure repeats; the argv is in the message.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "run_tool.h"

namespace plc_cell {
namespace {

class ArgvGenerator {
 public:
  explicit ArgvGenerator(uint32_t seed) : rng_(seed) {}

  std::string next() {
    static const std::vector<std::string> commands = {"sim", "check", "run", "fatek", "", "--help", "simulate", "-x"};
    std::string argv = one_of(commands);
    const int n = uniform(0, 7);
    for (int i = 0; i < n; ++i) argv += " " + option(argv);
    return argv;
  }

 private:
  std::string option(const std::string& command) {
    const std::string ex = std::string(PLC_CELL_SOURCE_DIR) + "/examples/";
    static const std::vector<std::string> files = {"conveyor/conveyor.yaml", "motion/homing.yaml", "hsc/rpm.yaml",
                                                   "oven/oven.il", "conveyor/conveyor.il", "missing.yaml", "", "hsc"};
    switch (uniform(0, 14)) {
      case 0: return "--config " + quote(ex + one_of(files));
      case 1: return "--program " + quote(ex + one_of(files));
      case 2: return "--duration " + duration();
      case 3: return "--scan " + duration();
      case 4: return "--watch " + quote(one_of({"R0", "DR4088", "X0,Y0", "R0:u", "R0:f32", "Q9", "R99999", "", ",,", "M1:hex"}));
      case 5: return "--set " + quote(one_of({"R0=1", "X0=1", "R0=-70000", "=", "R0", "Y0=on", "DR0=4294967296", "Z1=1"}));
      case 6: return "--trace " + quote(one_of({"/tmp/plc_cell_argv_trace.csv", "/nonexistent/dir/t.csv", ""}));
      case 7: return one_of({"--fatek-tcp", "--modbus-tcp"}) + " " +
                     quote(one_of({"127.0.0.1:0", "127.0.0.1:-1", "127.0.0.1:70000", "nohost", ":", "127.0.0.1"}));
      case 8: return one_of({"--fatek-serial", "--modbus-rtu", "--serial", "--modbus-gateway"}) + " " +
                     quote(one_of({"/nonexistent/tty", "/dev/null:9600:8N1", "/dev/null:0:9Z9", "", "x:y:z:w"}));
      case 9: return one_of({"--station", "--modbus-id", "--retries", "--rt-priority", "--fatek-max-connections",
                             "--modbus-gateway-retries", "--timeout"}) + " " + number();
      case 10: return one_of({"--fatek-writable", "--modbus-writable"}) + " " +
                      quote(one_of({"D0-D99", "none", "all", "D99-D0", "Q0-Q1", "", "M0-M99999"}));
      case 11: return one_of({"--persist-interval", "--fatek-idle-timeout", "--modbus-idle-timeout", "--modbus-gateway-wait"}) +
                      " " + duration();
      case 12: return command == "fatek" ? one_of({"status", "read R0 4", "write R0 1", "force Y0 on", "read", "loopback"})
                                         : "--tcp 127.0.0.1:1 --timeout 50";
      case 13: return junk();
      default: return "--" + junk();
    }
  }

  std::string duration() {
    return quote(one_of({"1ms", "10ms", "0.05s", "0", "-1s", "1h", "abc", "1e309s", "99999999999999999999ms", "", "5 ms"}));
  }
  std::string number() { return quote(one_of({"0", "1", "-1", "255", "256", "65536", "4294967296", "x", "", "1.5"})); }
  std::string junk() {
    std::string s;
    for (int i = uniform(0, 12); i > 0; --i) s += static_cast<char>(uniform(33, 126));
    return quote(s);
  }
  // Single quotes for sh; a quote inside is closed, escaped and reopened.
  static std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  }
  std::string one_of(const std::vector<std::string>& v) { return v[static_cast<size_t>(uniform(0, static_cast<int>(v.size()) - 1))]; }
  int uniform(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  std::mt19937 rng_;
};

TEST(CliArgvFuzz, EveryArgumentVectorEndsWithAStatusAndAReason) {
  ArgvGenerator gen(20261124);
  for (int i = 0; i < 300; ++i) {
    std::string argv = gen.next();
    // `run` without a duration runs until a signal: bound it like a user's Ctrl-C would.
    if (argv.rfind("run", 0) == 0) argv += " --duration 0.1s";
    const auto r = testing::run_tool(argv + " </dev/null");
    ASSERT_TRUE(r.status == 0 || r.status == 1 || r.status == 2) << "plc_cell " << argv << "\nstatus " << r.status << "\n" << r.out;
    if (r.status != 0)
      EXPECT_NE(r.out.find_first_not_of(" \n"), std::string::npos) << "plc_cell " << argv << ": refused without a reason";
  }
}

}  // namespace
}  // namespace plc_cell
