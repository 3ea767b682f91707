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
// FORMAT is omitted (7E1 for FATEK, 8E1 for Modbus RTU).
SerialSettings parse_serial_settings(const std::string& text, const std::string& default_format = "7E1");
// "HOST:PORT" (HOST may be empty for 127.0.0.1); throws plc_cell::Error.
void parse_host_port(const std::string& text, std::string* host, int* port);

}  // namespace plc_cell
