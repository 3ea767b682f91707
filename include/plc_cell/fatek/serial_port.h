#pragma once
// Small fd helpers with timeouts for the FATEK lines (serial or TCP): the io layer's
// (io/transport.h). The serial device itself is opened by io/serial_line.h.
#include "plc_cell/io/transport.h"

namespace plc_cell {
namespace fatek {

using plc_cell::wait_readable;
using plc_cell::write_all;

}  // namespace fatek
}  // namespace plc_cell
