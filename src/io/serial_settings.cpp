#include "plc_cell/io/serial_settings.h"

#include <cctype>

#include "plc_cell/core/error.h"

namespace plc_cell {

std::string SerialSettings::format() const {
  return std::to_string(data_bits) + parity + std::to_string(stop_bits);
}

std::string SerialSettings::to_string() const { return device + ":" + std::to_string(baud) + ":" + format(); }

static bool all_digits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

SerialSettings parse_serial_settings(const std::string& text, const std::string& default_format, int default_baud) {
  SerialSettings s;
  s.baud = default_baud;
  const auto bad = [&](const std::string& why) { return Error("serial port '" + text + "': " + why); };
  const auto c1 = text.find(':');
  s.device = text.substr(0, c1);
  if (s.device.empty()) throw bad("no device (expected DEVICE[:BAUD[:FORMAT]], e.g. /dev/ttyUSB0:9600:7E1)");
  std::string fmt = default_format;
  if (c1 != std::string::npos) {
    const auto c2 = text.find(':', c1 + 1);
    const std::string baud = text.substr(c1 + 1, c2 == std::string::npos ? std::string::npos : c2 - c1 - 1);
    if (!all_digits(baud) || baud.size() > 7) throw bad("baud '" + baud + "' is not a number");
    s.baud = std::stoi(baud);
    if (s.baud < 1200 || s.baud > 921600) throw bad("baud " + baud + " outside 1200..921600");
    if (c2 != std::string::npos) fmt = text.substr(c2 + 1);
  }
  if (fmt.size() != 3 || (fmt[0] != '7' && fmt[0] != '8') ||
      (std::toupper(static_cast<unsigned char>(fmt[1])) != 'N' && std::toupper(static_cast<unsigned char>(fmt[1])) != 'E' &&
       std::toupper(static_cast<unsigned char>(fmt[1])) != 'O') ||
      (fmt[2] != '1' && fmt[2] != '2'))
    throw bad("format '" + fmt + "' (expected data bits 7/8, parity N/E/O, stop bits 1/2, e.g. 7E1 or 8N1)");
  s.data_bits = fmt[0] - '0';
  s.parity = static_cast<char>(std::toupper(static_cast<unsigned char>(fmt[1])));
  s.stop_bits = fmt[2] - '0';
  return s;
}

void parse_host_port(const std::string& text, std::string* host, int* port) {
  const auto c = text.rfind(':');
  if (c == std::string::npos) throw Error("'" + text + "': expected HOST:PORT, e.g. 127.0.0.1:500");
  const std::string p = text.substr(c + 1);
  if (!all_digits(p)) throw Error("'" + text + "': port '" + p + "' is not a number (expected HOST:PORT, e.g. 127.0.0.1:500)");
  if (p.size() > 5 || std::stoi(p) > 65535) throw Error("'" + text + "': port '" + p + "' is not 0..65535");
  *host = text.substr(0, c);
  if (host->empty()) *host = "127.0.0.1";
  *port = std::stoi(p);
}

}  // namespace plc_cell
