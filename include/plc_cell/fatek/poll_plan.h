#pragma once
// Coalescing poll groups into few legal FATEK frames: elements of one type form runs
// (bridging small gaps); each run yields full 44/46 block frames (256 discretes / 64 words /
// 32 DW) and a remainder; remainders are packed first-fit-decreasing into frames of weight
// 64 - a frame with one remainder is a block read, one with several a 48 mixed read.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/config/register_groups.h"
#include "plc_cell/fatek/client.h"

namespace plc_cell {
namespace fatek {

// Parsed by parse_register_span: "R100", "R100:10", "DR0:4", "X0:16".
using PollItem = RegisterSpan;

struct PollPlan {
  std::vector<Request> requests;  // station is filled in by the client
};

// Gaps up to this many unrequested elements are read through to join two runs.
constexpr uint32_t kMaxGap = 4;

PollPlan plan_poll(const std::vector<PollItem>& items);
// Executes the plan; returns each item's values in item order. Throws like Client.
std::vector<std::vector<uint32_t>> run_poll(Client& c, const std::vector<PollItem>& items, const PollPlan& plan);

}  // namespace fatek
}  // namespace plc_cell
