#pragma once
// Serial line settings written as DEVICE[:BAUD[:FORMAT]], e.g. /dev/ttyUSB0:9600:7E1.
#include <string>

namespace plc_cell {

struct SerialSettings {
  std::string device;
  int baud = 9600;
  int data_bits = 7;   // the FBs default is 7E1
  char parity = 'E';   // 'N', 'E' or 'O'
  int stop_bits = 1;

  std::string format() const;     // "7E1"
  std::string to_string() const;  // "/dev/ttyS0:9600:7E1"
};

// Throws plc_cell::Error naming the text and the reason. default_format applies when
// FORMAT is omitted (7E1 for FATEK, 8E1 for Modbus RTU, 8N1 for the TRi), default_baud
// when BAUD is (9600; the TRi's 38400).
SerialSettings parse_serial_settings(const std::string& text, const std::string& default_format = "7E1",
                                     int default_baud = 9600);
// "HOST:PORT" (HOST may be empty for 127.0.0.1; PORT 0..65535, 0 for a server to pick one);
// throws plc_cell::Error saying whether the port is missing, not a number or out of range.
void parse_host_port(const std::string& text, std::string* host, int* port);

}  // namespace plc_cell
