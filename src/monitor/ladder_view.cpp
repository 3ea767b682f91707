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

nlohmann::json LadderView::json() const { return ladder::to_json(impl_->layout); }

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
