#include "plc_cell/coverage/recorder.h"

#include <algorithm>

#include "plc_cell/core/error.h"
#include "plc_cell/coverage/same_program.h"

namespace plc_cell {
namespace coverage {

namespace {

std::vector<std::string> fun_names_of(const Program& p, const FunctionTable& functions) {
  std::vector<std::string> names(p.code.size());
  for (size_t i = 0; i < p.code.size(); ++i)
    if (p.code[i].op == Op::Fun)
      if (const FunctionSpec* spec = functions.find(p.code[i].fun)) names[i] = spec->mnemonic;
  return names;
}

std::vector<NetworkShape> shapes_of(const Program& p, const std::vector<std::string>& fun_names) {
  std::vector<NetworkShape> shapes;
  for (const Network& n : networks_of(p, std::vector<uint8_t>(p.code.size(), 0), fun_names, {})) {
    shapes.emplace_back();
    for (const Item& it : n.items)
      (it.kind == ItemKind::Contact ? shapes.back().contacts : shapes.back().outcomes).push_back(it.index);
  }
  return shapes;
}

}  // namespace

const std::string& Recorder::program_file() const {
  static const std::string none;
  return program_ ? program_->file : none;
}

const Program& Recorder::program() const {
  if (!program_) throw Error("coverage: nothing recorded yet");
  return *program_;
}

void Recorder::attach(Plc& plc, const SignalNames& names) {
  for (const auto& a : attached_)
    if (a.plc == &plc) throw Error("coverage: this PLC is already being recorded");
  std::unique_ptr<uint8_t[]> seen;
  std::unique_ptr<McdcSampler> sampler;
  plc.locked([&](ScanEngine& engine, Memory&) {
    Interpreter& interp = engine.interpreter();
    const Program& p = interp.program();
    if (!interp.loaded()) throw Error("coverage: the PLC has no program to record");
    if (interp.recording()) throw Error("coverage: " + p.file + " is already being recorded by another recorder");
    if (program_) {
      const std::string why = program_difference(*program_, p);
      if (!why.empty())
        throw Error("coverage: " + p.file + " is not the program this recorder holds (" + program_->file +
                    "): " + why + "; record each program with its own recorder");
    } else {
      program_ = std::make_unique<Program>(p);
      fun_names_ = fun_names_of(p, plc.functions());
      seen_.assign(p.code.size(), 0);
    }
    seen.reset(new uint8_t[p.code.size()]());
    interp.record_into(seen.get());
    sampler = std::make_unique<McdcSampler>(shapes_of(p, fun_names_), seen.get(), p.code.size());
    engine.add_hook(sampler.get());
  });
  attached_.push_back({&plc, std::move(seen), std::move(sampler)});
  if (names_.empty()) names_ = names;
}

void Recorder::detach(Plc& plc) {
  const auto it = std::find_if(attached_.begin(), attached_.end(), [&](const Attachment& a) { return a.plc == &plc; });
  if (it == attached_.end()) return;
  plc.locked([&](ScanEngine& engine, Memory&) {
    // A program loaded since attach already ended the recording; this stops nothing else's.
    if (engine.interpreter().recording() == it->seen.get()) engine.interpreter().record_into(nullptr);
    engine.remove_hook(it->sampler.get());
  });
  it->sampler->drain(seen_);
  vectors_.merge(it->sampler->vectors());
  ++runs_;
  attached_.erase(it);
}

}  // namespace coverage
}  // namespace plc_cell
