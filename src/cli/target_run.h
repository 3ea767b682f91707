#pragma once
// `plc_cell test --target`: the scenario files' cases on a PLC over its link, in wall-clock
// time, leaving it as it was found (docs/testing-on-hardware.md).
#include <string>
#include <vector>

#include "args.h"

namespace plc_cell {
namespace cli {

// The options `test` takes for it (besides -k, --junit and --record, which it shares).
const std::vector<std::string>& target_options();

// The whole run; its exit status: 0 when every case passed and the PLC was left as found.
int cmd_test_on_target(const Args& args);

}  // namespace cli
}  // namespace plc_cell
