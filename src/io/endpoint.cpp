#include "plc_cell/io/endpoint.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace {

const char* const kExpected = "expected HOST:PORT or a serial device path such as /dev/ttyUSB0[:BAUD[:FORMAT]]";

Error bad(const std::string& text, const std::string& why) { return Error("endpoint '" + text + "': " + why); }

}  // namespace

Endpoint parse_endpoint(const std::string& text, const LineDefaults& line) {
  if (text.empty()) throw Error(std::string("empty endpoint: ") + kExpected);
  Endpoint e;
  const auto colon = text.find(':');
  if (text.substr(0, colon).find('/') != std::string::npos) {
    e.serial = parse_serial_settings(text, line.format, line.baud);
    return e;
  }
  if (colon == std::string::npos) throw bad(text, kExpected);
  try {
    parse_host_port(text, &e.host, &e.port);
  } catch (const Error& x) {
    throw Error(std::string("endpoint ") + x.what());
  }
  if (e.port == 0) throw bad(text, "port 0: a client needs the port its device listens on (1..65535)");
  return e;
}

std::unique_ptr<Transport> client_transport(const std::string& text, const LineDefaults& line) {
  const Endpoint e = parse_endpoint(text, line);
  if (!e.serial) return tcp_transport(e.host, e.port);
  struct stat st {};
  const std::string& device = e.serial->device;
  if (::stat(device.c_str(), &st) != 0)
    throw bad(text, errno == ENOENT ? "no such device " + device : device + ": " + std::strerror(errno));
  if (!S_ISCHR(st.st_mode)) throw bad(text, device + " is not a serial device (not a character device)");
  return serial_transport(*e.serial);
}

}  // namespace plc_cell
