// plc_cell: the soft PLC from the command line, no ROS master needed.
#include <algorithm>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "args.h"
#include "commands.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/core/error.h"

namespace {

const char* placeholder(plc_cell::SettingType t) {
  using plc_cell::SettingType;
  switch (t) {
    case SettingType::HostPort: return "HOST:PORT";
    case SettingType::SerialLine: return "DEV[:BAUD[:FMT]]";
    case SettingType::Integer: return "N";
    case SettingType::Duration: return "DURATION";
    case SettingType::Writable: return "RANGES";
    case SettingType::Boolean: return "true|false";
    case SettingType::Text: break;
  }
  return "TEXT";
}

// A command's usage lines in a column as wide as the longest name and a space: each line
// is re-indented, so a longer name added to the list moves every line and never overruns.
void command_lines(std::ostream& out) {
  size_t width = 0;
  for (const auto& c : plc_cell::cli::commands()) width = std::max(width, std::string(c.name).size() + 1);
  for (const auto& c : plc_cell::cli::commands()) {
    std::istringstream lines(c.usage);
    std::string line, name = c.name;
    while (std::getline(lines, line)) {
      line.erase(0, line.find_first_not_of(' '));
      name.resize(width, ' ');
      out << "  " << name << line << "\n";
      name.clear();
    }
  }
}

// The commands and the server options come from their lists (cli::commands(), the server
// kinds' schemas): a new command or server kind lists itself.
void usage(std::ostream& out) {
  out << "usage: plc_cell COMMAND [options]\n\ncommands:\n";
  command_lines(out);
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
    for (const auto& c : plc_cell::cli::commands())
      if (cmd == c.name) return c.run(args);
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
