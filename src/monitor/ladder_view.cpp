#include "ladder_view.h"

namespace plc_cell {
namespace monitor {

// Until the ladder library is linked: networks split at ORG, shown as their IL lines.
struct LadderView::Impl {
  std::vector<std::pair<size_t, size_t>> nets;  // [first, last) instruction
};

namespace {
bool starts_network(Op op) { return op == Op::Org || op == Op::OrgNot || op == Op::OrgUp || op == Op::OrgDown; }
}  // namespace

LadderView::LadderView(std::shared_ptr<const ProgramView> program)
    : program_(std::move(program)), impl_(std::make_unique<Impl>()) {
  const auto& code = program_->program.code;
  for (size_t i = 0; i < code.size(); ++i)
    if (starts_network(code[i].op) || impl_->nets.empty()) impl_->nets.push_back({i, i + 1});
    else impl_->nets.back().second = i + 1;
}

LadderView::~LadderView() = default;

size_t LadderView::networks() const { return impl_->nets.size(); }

nlohmann::json LadderView::json() const {
  nlohmann::json j = {{"file", program_->file}, {"version", program_->version}};
  j["networks"] = nlohmann::json::array();
  for (size_t n = 0; n < impl_->nets.size(); ++n) {
    nlohmann::json il = nlohmann::json::array();
    for (size_t i = impl_->nets[n].first; i < impl_->nets[n].second; ++i)
      il.push_back({{"line", program_->program.code[i].line}, {"text", ""}});
    j["networks"].push_back({{"index", n},
                             {"line", program_->program.code[impl_->nets[n].first].line},
                             {"drawable", false},
                             {"reason", "no ladder layout in this build"},
                             {"il", il},
                             {"elements", nlohmann::json::array()},
                             {"wires", nlohmann::json::array()}});
  }
  j["signals"] = nlohmann::json::object();
  for (const auto& [name, a] : program_->signals) j["signals"][format_address(a)] = name;
  return j;
}

std::vector<Address> LadderView::addresses(size_t n) const {
  std::vector<Address> out;
  if (n >= impl_->nets.size()) return out;
  for (size_t i = impl_->nets[n].first; i < impl_->nets[n].second; ++i) {
    const auto& in = program_->program.code[i];
    if (in.op <= Op::Rst) out.push_back(in.addr);
  }
  return out;
}

std::vector<int> LadderView::flow(size_t, const Lookup&, const Lookup&) const { return {}; }

}  // namespace monitor
}  // namespace plc_cell
