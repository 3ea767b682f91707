#include "plc_cell/temp/linear_conversion.h"

#include <algorithm>
#include <cmath>

#include "plc_cell/core/area.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/temp/analog_codes.h"

namespace plc_cell {
namespace temp {
namespace {

using R = OperandRole;

// How many of n registers from a fit in its area (a table must not run off the end).
int64_t fit(const BoundOperand& o, int64_t n) {
  return std::max<int64_t>(0, std::min<int64_t>(n, int64_t(Memory::word_count(o.addr.area)) - o.addr.index));
}

std::string check_n(const std::vector<Operand>& ops, size_t i) {
  const Operand& n = ops.at(i);
  if (n.kind == Operand::Kind::Const && (n.k < 1 || n.k > 256)) return "N must be 1..256";
  return {};
}

}  // namespace

int32_t linear_convert(int32_t s, int32_t smin, int32_t smax, int32_t dmin, int32_t dmax) {
  if (smax == smin) return dmin;
  const double d = dmin + double(s - smin) * double(dmax - dmin) / double(smax - smin);
  return static_cast<int32_t>(std::clamp(std::round(d), -32768.0, 32767.0));
}

void add_linear_conversion_functions(FunctionTable& t) {
  {
    FunctionSpec s;
    s.number = 32;
    s.mnemonic = "ADCNV";
    s.operands = {{"Md", R::Const}, {"S", R::Register}, {"D", R::Register}, {"N", R::Source}};
    s.allow_32 = false;
    s.check = [](const std::vector<Operand>& ops) -> std::string {
      if (ops.at(0).k != 0 && ops.at(0).k != 1) return "Md must be 0 (unipolar code) or 1 (bipolar code)";
      return check_n(ops, 3);
    };
    s.handler = [](ExecContext& c, const BoundOperand* o) {
      const int64_t n = std::min(fit(o[1], c.get(o[3])), fit(o[2], c.get(o[3])));
      for (int64_t i = 0; i < n; ++i)
        o[2].w[i] = static_cast<uint16_t>(offset_4_20(static_cast<int16_t>(o[1].w[i]), o[0].k == 1));
    };
    t.add(s);
  }
  {
    FunctionSpec s;
    s.number = 33;
    s.mnemonic = "LCNV";
    s.operands = {{"S", R::Register}, {"Ts", R::Register, false, 4}, {"D", R::Register}, {"N", R::Source}};
    s.allow_32 = false;
    s.check = [](const std::vector<Operand>& ops) { return check_n(ops, 3); };
    s.handler = [](ExecContext& c, const BoundOperand* o) {
      const int64_t n = std::min(fit(o[0], c.get(o[3])), fit(o[2], c.get(o[3])));
      const auto ts = [&](int k) { return int32_t(int16_t(o[1].w[k])); };
      // Read every source before writing: S and D may overlap.
      std::vector<int16_t> in(o[0].w, o[0].w + n);
      for (int64_t i = 0; i < n; ++i)
        o[2].w[i] = static_cast<uint16_t>(linear_convert(in[i], ts(0), ts(1), ts(2), ts(3)));
    };
    t.add(s);
  }
}

}  // namespace temp
}  // namespace plc_cell
