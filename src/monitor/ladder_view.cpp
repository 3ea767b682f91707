#include "ladder_view.h"

#include "plc_cell/ladder/flow.h"
#include "plc_cell/ladder/json.h"
#include "plc_cell/ladder/layout.h"

namespace plc_cell {
namespace monitor {

struct LadderView::Impl {
  ladder::Layout layout;
};

LadderView::LadderView(std::shared_ptr<const ProgramView> program, const FunctionTable* functions)
    : program_(std::move(program)), impl_(std::make_unique<Impl>()) {
  static const FunctionTable core = FunctionTable::with_core_functions();
  impl_->layout = ladder::layout(program_->program, program_->text, program_->signals, functions ? functions : &core);
  impl_->layout.file = program_->file;
  impl_->layout.version = program_->version;
}

LadderView::~LadderView() = default;

size_t LadderView::networks() const { return impl_->layout.networks.size(); }

// Each network's number as a person reads it: counted from 1 over the networks that start
// with ORG, as coverage and mutation testing count them, so that "network 5" is the same
// network everywhere. A flow instruction drawn alone (LBL, RTS, END, ...) and IL that does
// not start with ORG are no network: they have none (null).
nlohmann::json LadderView::json() const {
  nlohmann::json j = ladder::to_json(impl_->layout);
  const auto& code = program_->program.code;
  uint32_t number = 0;
  for (size_t k = 0; k < impl_->layout.networks.size(); ++k) {
    const uint32_t first = impl_->layout.networks[k].first;
    const Op op = first < code.size() ? code[first].op : Op::End;
    const bool org = op == Op::Org || op == Op::OrgNot || op == Op::OrgUp || op == Op::OrgDown;
    j["networks"][k]["number"] = org ? nlohmann::json(++number) : nlohmann::json(nullptr);
  }
  return j;
}

std::vector<Address> LadderView::addresses(size_t n) const {
  if (n >= impl_->layout.networks.size()) return {};
  return ladder::addresses(impl_->layout.networks[n]);
}

std::vector<int> LadderView::flow(size_t n, const Lookup& value, const Lookup& prev) const {
  if (n >= impl_->layout.networks.size()) return {};
  return ladder::flow(impl_->layout.networks[n], value, prev).on;
}

}  // namespace monitor
}  // namespace plc_cell
