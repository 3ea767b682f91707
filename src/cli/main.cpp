// plc_cell: the soft PLC from the command line, no ROS master needed.
#include <iostream>
#include <string>
#include <vector>

#include "args.h"
#include "commands.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/core/error.h"

namespace {

const char* kUsage =
    "usage: plc_cell COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  sim    --program FILE [--config FILE] --duration 2.5s [--scan 1ms]\n"
    "         [--set ADDR=VALUE ...] [--watch ADDR,...] [--trace FILE.csv]\n"
    "         run the program in virtual time and print the watched values\n"
    "  run    --program FILE [--config FILE] [--scan 1ms] [--duration T] [--rt-priority N]\n"
    "         run the soft PLC in real time until interrupted\n"
    "  check  --program FILE [--config CELL.yaml]   parse a program and report every error\n"
    // @usage: subsystems add their commands' usage lines here
    "  fatek  (--tcp HOST:PORT | --serial DEV[:BAUD[:FMT]]) [--station N] [--timeout MS]\n"
    "         [--retries N] status|run|stop|read ADDR [COUNT]|write ADDR VALUE...|\n"
    "         force ADDR on|off|enable|disable|disabled ADDR [COUNT]|loopback TEXT\n"
    "         talk to a FATEK FBs-PLC (or plc_cell run --fatek-tcp/--fatek-serial)\n"
    "  run    ... [--persist FILE] [--persist-interval DURATION]\n"
    "         keep the retentive ranges in FILE across restarts and crashes (default 100ms)\n"
    "  run    ... [--SERVER-SETTING VALUE ...]   serve the cell's protocols (below); each\n"
    "         option overrides the cell YAML's servers.SERVER.SETTING\n";

const char* placeholder(plc_cell::SettingType t) {
  using plc_cell::SettingType;
  switch (t) {
    case SettingType::HostPort: return "HOST:PORT";
    case SettingType::SerialLine: return "DEV[:BAUD[:FMT]]";
    case SettingType::Integer: return "N";
    case SettingType::Duration: return "DURATION";
    case SettingType::Writable: return "RANGES";
    case SettingType::Text: break;
  }
  return "TEXT";
}

// The server options come from the server kinds' schemas: a new kind lists itself.
void usage(std::ostream& out) {
  out << kUsage;
  for (const auto& k : plc_cell::Cell::server_kinds()) {
    out << "\n" << k.title << ":\n";
    for (const auto& s : k.settings) {
      std::string names = k.option(s) + " " + placeholder(s.type);
      if (!s.cli_alias.empty()) names += " (or --" + s.cli_alias + ")";
      if (!s.fallback.empty()) names += " [" + s.fallback + "]";
      out << "  " << names << "\n      " << s.help << "\n";
    }
  }
  out << "\nexit status: 0 ok, 1 program/config/runtime error, 2 usage error\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "-h" || args[0] == "--help" || args[0] == "help") {
    usage(std::cout);
    return args.empty() ? 2 : 0;
  }
  const std::string cmd = args[0];
  args.erase(args.begin());
  try {
    if (cmd == "sim") return plc_cell::cli::cmd_sim(args);
    if (cmd == "run") return plc_cell::cli::cmd_run(args);
    if (cmd == "check") return plc_cell::cli::cmd_check(args);
    // @commands: subsystems dispatch their commands here
    if (cmd == "fatek") return plc_cell::cli::cmd_fatek(args);
    std::cerr << "plc_cell: unknown command '" << cmd << "'\n";
    usage(std::cerr);
    return 2;
  } catch (const plc_cell::cli::UsageError& e) {
    std::cerr << "plc_cell " << cmd << ": " << e.what() << "\n";
    usage(std::cerr);
    return 2;
  } catch (const plc_cell::Error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "plc_cell " << cmd << ": " << e.what() << "\n";
    return 1;
  }
}
