#pragma once
// Where a master reaches its device when one text says it (plc_cell monitor --fatek, --tri):
// HOST:PORT for TCP, or DEVICE[:BAUD[:FORMAT]] for a serial line. A device is a path, so the
// text is a serial line when a '/' comes before its first ':' (/dev/ttyUSB0:9600:7E1,
// ./ttyV0); anything else must be HOST:PORT. Masters configured with separate TCP and serial
// keys (the bridges' tcp/serial, FUN150/151's ports) parse each key as what it is instead.
#include <memory>
#include <optional>
#include <string>

#include "plc_cell/io/serial_settings.h"
#include "plc_cell/io/transport.h"

namespace plc_cell {

struct Endpoint {
  std::string host;  // TCP: the host (127.0.0.1 when the text gives none) and a port 1..65535
  int port = 0;
  std::optional<SerialSettings> serial;  // set for a serial line (host and port unused)
};

// The serial line's format and baud when the text leaves them out (the FBs' 9600 7E1; the
// TRi's 38400 8N1).
struct LineDefaults {
  std::string format = "7E1";
  int baud = 9600;
};

// Throws plc_cell::Error saying what is wrong with the text: empty, neither HOST:PORT nor a
// device path, a port that is missing, not a number or not 1..65535 (a client cannot
// connect to port 0), a baud or format that does not parse.
Endpoint parse_endpoint(const std::string& text, const LineDefaults& line = {});

// The transport to the endpoint, not connected yet: its first transaction connects (a PLC
// that is not up yet is a link down, which its user reports and retries). The text is
// checked first as parse_endpoint does, and a serial device must exist and be a character
// device: a mistyped path is an error here, not a link that never comes up.
std::unique_ptr<Transport> client_transport(const std::string& text, const LineDefaults& line = {});

}  // namespace plc_cell
