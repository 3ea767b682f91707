#include "plc_cell/core/function_table.h"

#include <cctype>

#include "plc_cell/core/error.h"

namespace plc_cell {

static std::string upper(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

void FunctionTable::add(FunctionSpec spec) {
  if (spec.number >= by_number_.size()) throw Error("function number " + std::to_string(spec.number) + " too large");
  if (by_number_[spec.number] >= 0) throw Error("FUN " + std::to_string(spec.number) + " registered twice");
  if (find(spec.mnemonic)) throw Error("mnemonic " + spec.mnemonic + " registered twice");
  if (spec.inputs.empty() || spec.inputs.size() > 4) throw Error("a function takes 1 to 4 inputs");
  spec.mnemonic = upper(spec.mnemonic);
  by_number_[spec.number] = static_cast<int>(specs_.size());
  specs_.push_back(std::move(spec));
}

const FunctionSpec* FunctionTable::find(uint16_t number) const {
  if (number >= by_number_.size() || by_number_[number] < 0) return nullptr;
  return &specs_[by_number_[number]];
}

void FunctionTable::add_unavailable(uint16_t number, const std::string& mnemonic, const std::string& why) {
  unavailable_.push_back({number, upper(mnemonic), why});
}

std::string FunctionTable::why_unavailable(uint16_t number) const {
  for (const auto& u : unavailable_)
    if (u.number == number) return "FUN " + std::to_string(u.number) + " " + u.mnemonic + ": " + u.why;
  return "";
}

std::string FunctionTable::why_unavailable(const std::string& mnemonic) const {
  const std::string m = upper(mnemonic);
  for (const auto& u : unavailable_)
    if (u.mnemonic == m) return why_unavailable(u.number);
  return "";
}

const FunctionSpec* FunctionTable::find(const std::string& mnemonic) const {
  const std::string u = upper(mnemonic);
  for (const auto& s : specs_)
    if (s.mnemonic == u) return &s;
  return nullptr;
}

}  // namespace plc_cell
