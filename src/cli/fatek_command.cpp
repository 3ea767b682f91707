// plc_cell fatek: a FATEK master on the command line; and the FATEK servers of plc_cell run.
#include <cstdio>
#include <iostream>
#include <memory>

#include "args.h"
#include "plc_cell/config/cell_config.h"
#include "commands.h"
#include "plc_cell/core/error.h"
#include "plc_cell/fatek/client.h"

namespace plc_cell {
namespace cli {
namespace {

int parse_int(const std::string& s, const std::string& what, long lo, long hi) {
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 0);
  if (s.empty() || *end || v < lo || v > hi)
    throw UsageError(what + " must be a number in " + std::to_string(lo) + ".." + std::to_string(hi) + ", not '" + s + "'");
  return int(v);
}

uint32_t parse_value(const std::string& s) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(s.c_str(), &end, 0);  // 123, 0x7B
  if (s.empty() || *end || s[0] == '-' || v > 0xFFFFFFFFull) throw UsageError("bad value '" + s + "'");
  return uint32_t(v);
}

void print_status(const fatek::PlcStatus& s) {
  std::printf("%s", s.run ? "RUN" : "STOP");
  if (s.status1 & 0x04) std::printf(", ladder checksum error / no program");
  if (s.status1 & 0x10) std::printf(", watchdog timeout");
  if (s.status1 & 0x40) std::printf(", emergency stop");
  std::printf("\nstatus bytes:");
  for (uint8_t b : s.bytes) std::printf(" %02X", b);
  std::printf("\n");
}

void print_value(const Address& a, uint32_t v) {
  if (a.width == Width::Bit)
    std::printf("%-8s %s\n", format_address(a).c_str(), v ? "1" : "0");
  else if (a.width == Width::Word)
    std::printf("%-8s %u (0x%04X, %d)\n", format_address(a).c_str(), v, v, int(int16_t(v)));
  else
    std::printf("%-8s %u (0x%08X, %d)\n", format_address(a).c_str(), v, v, int(int32_t(v)));
}

}  // namespace

int cmd_fatek(const std::vector<std::string>& argv) {
  Args args(argv, {"tcp", "serial", "station", "timeout", "retries"});
  if (args.has("tcp") == args.has("serial")) throw UsageError("give exactly one of --tcp HOST:PORT or --serial DEVICE");
  const auto& pos = args.positional();
  if (pos.empty()) throw UsageError("missing command (status, run, stop, read, write, force, disabled, loopback)");
  fatek::ClientOptions opt;
  opt.station = parse_int(args.get("station", "1"), "--station", 0, 254);
  opt.timeout_ms = parse_int(args.get("timeout", "1000"), "--timeout", 1, 600000);
  opt.retries = parse_int(args.get("retries", "2"), "--retries", 0, 100);
  const std::string cmd = pos[0];
  auto need = [&](size_t lo, size_t hi) {
    if (pos.size() - 1 < lo || pos.size() - 1 > hi) throw UsageError("wrong number of arguments for '" + cmd + "'");
  };
  // Validate the command line before touching the line.
  if (cmd == "status" || cmd == "run" || cmd == "stop") need(0, 0);
  else if (cmd == "read" || cmd == "disabled") need(1, 2);
  else if (cmd == "write") need(2, 100000);
  else if (cmd == "force") need(2, 2);
  else if (cmd == "loopback") need(1, 1);
  else throw UsageError("unknown fatek command '" + cmd + "'");
  if (opt.station == 0 && (cmd == "status" || cmd == "read" || cmd == "disabled" || cmd == "loopback"))
    throw UsageError("station 0 is broadcast: only run, stop, write and force");

  std::unique_ptr<fatek::Transport> t = args.has("tcp")
                                            ? fatek::tcp_transport(args.get("tcp"))
                                            : fatek::serial_transport(parse_serial_settings(args.get("serial"), "7E1"));
  fatek::Client client(std::move(t), opt);
  try {
    if (cmd == "status") {
      print_status(client.status());
    } else if (cmd == "run" || cmd == "stop") {
      client.set_run(cmd == "run");
      std::printf("%s\n", cmd == "run" ? "RUN" : "STOP");
    } else if (cmd == "read" || cmd == "disabled") {
      const Address a = parse_address(pos[1]);
      const uint32_t n = pos.size() > 2 ? uint32_t(parse_int(pos[2], "COUNT", 1, 100000)) : 1;
      if (cmd == "read") {
        const auto v = client.read(a, n);
        for (uint32_t i = 0; i < n; ++i) print_value(offset_address(a, i), v[i]);
      } else {
        const auto v = client.read_disabled(a, n);
        for (uint32_t i = 0; i < n; ++i)
          std::printf("%-8s %s\n", format_address(offset_address(a, i)).c_str(), v[i] ? "disabled" : "enabled");
      }
    } else if (cmd == "write") {
      const Address a = parse_address(pos[1]);
      std::vector<uint32_t> values;
      for (size_t i = 2; i < pos.size(); ++i) values.push_back(parse_value(pos[i]));
      client.write(a, values);
      std::printf("wrote %zu value(s) from %s\n", values.size(), format_address(a).c_str());
    } else if (cmd == "force") {
      const Address a = parse_address(pos[1]);
      const std::string& what = pos[2];
      fatek::Action act;
      if (what == "on") act = fatek::Action::Set;
      else if (what == "off") act = fatek::Action::Reset;
      else if (what == "enable") act = fatek::Action::Enable;
      else if (what == "disable") act = fatek::Action::Disable;
      else throw UsageError("force takes on, off, enable or disable, not '" + what + "'");
      if (a.width != Width::Bit) throw UsageError("force needs a single discrete (X, Y, M, S, T, C)");
      client.control(a, act);
      std::printf("%s %s\n", format_address(a).c_str(), what.c_str());
    } else if (cmd == "loopback") {
      const std::string echo = client.loopback(pos[1]);
      std::printf("%s\n", echo.c_str());
    }
  } catch (const fatek::PlcError& e) {
    std::cerr << "plc_cell fatek: " << e.what() << "\n";
    return 1;
  } catch (const fatek::CommError& e) {
    std::cerr << "plc_cell fatek: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

Command fatek_command() {
  return {"fatek",
          "(--tcp HOST:PORT | --serial DEV[:BAUD[:FMT]]) [--station N] [--timeout MS]\n"
          "         [--retries N] status|run|stop|read ADDR [COUNT]|write ADDR VALUE...|\n"
          "         force ADDR on|off|enable|disable|disabled ADDR [COUNT]|loopback TEXT\n"
          "         talk to a FATEK FBs-PLC (or plc_cell run --fatek-tcp/--fatek-serial)\n",
          cmd_fatek};
}

}  // namespace cli
}  // namespace plc_cell
