#pragma once
// What the remote source's tests share: the conveyor example whose IL draws the ladder, the
// text of a refusal, and a RemoteSource over a link to a port on loopback.
#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "plc_cell/core/error.h"
#include "plc_cell/remote/remote_source.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace remote_test {

const std::string kConveyorDir = std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/";
const std::string kConveyorIl = kConveyorDir + "conveyor.il";

// What f throws, or "accepted".
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "accepted";
}

// A link's options for the PLC serving on 127.0.0.1:port.
template <class Options>
Options on_loopback(int port, int timeout_ms = 1000) {
  Options o;
  o.endpoint = "127.0.0.1:" + std::to_string(port);
  o.timeout_ms = timeout_ms;
  return o;
}

// The monitor's source over a Link made from its options, the ladder drawn from the conveyor.
// Its forced points are read again only every forced_every (an hour: not during a test
// unless it says so).
template <class Link, class Options>
std::unique_ptr<remote::RemoteSource> conveyor_source(const Options& o,
                                                      std::chrono::milliseconds retry_after = std::chrono::seconds(1),
                                                      std::chrono::milliseconds forced_every = std::chrono::hours(1)) {
  return std::make_unique<remote::RemoteSource>(std::make_unique<Link>(o),
                                                remote::load_program_view(kConveyorIl, SoftCell::functions()),
                                                retry_after, forced_every);
}

}  // namespace remote_test
}  // namespace plc_cell
