#include "plc_cell/temp/analog_modules.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/temp/sensor_signal.h"

namespace plc_cell {
namespace temp {
namespace {

constexpr uint64_t kWatchdogUs = 500000;  // "not serviced by CPU for 0.5 second" (A:6218)

struct Kind {
  const char* name;
  int ai, ao;
};
// The AI part of the FBs-2A4TC/2A4RTD (A:7206-A:7370) is an AI module of 2 channels,
// "the same as the analog input modules" (its temperature part is in modules.temperature).
const Kind kKinds[] = {{"6AD", 6, 0},   {"4A2D", 4, 2},  {"4DA", 0, 4},
                       {"2DA", 0, 2},   {"2A4TC", 2, 0}, {"2A4RTD", 2, 0}};
const Kind kBoards[] = {{"B4AD", 4, 0}, {"B2DA", 0, 2}, {"B2A1D", 2, 1}};

// The inputs and outputs lists of a module or board with ai inputs and ao outputs.
void parse_channels(const std::string& file, const YAML::Node& m, const std::string& mk, const std::string& type,
                    int ai, int ao, std::vector<AnalogInputDef>* ins, std::vector<AnalogOutputDef>* outs) {
  const YamlReader r(file);
  if (const YAML::Node in = m["inputs"]) {
    if (!in.IsSequence() || int(in.size()) > ai)
      r.fail(in, mk + ".inputs", "a list of at most " + std::to_string(ai) + " inputs for a " + type);
    for (size_t j = 0; j < in.size(); ++j) {
      const std::string ik = mk + ".inputs[" + std::to_string(j) + "]";
      r.only(in[j], ik, {"name", "current", "value", "plant", "plant_range", "offset", "conditioning"});
      AnalogInputDef a;
      if (in[j]["name"]) a.name = r.str(in[j]["name"], ik + ".name");
      if (in[j]["current"]) a.current = r.boolean(in[j]["current"], ik + ".current");
      if (const YAML::Node v = in[j]["value"]) {
        // A bare number is in the terminal's unit (mA with current: true, else V); with a
        // unit, mA means the I terminal and V the V terminal.
        const std::string text = v.IsScalar() ? v.as<std::string>() : "";
        Quantity q;
        bool unit = false;
        try {
          q = parse_quantity(text);
          unit = true;
        } catch (const Error& e) {
          if (text.find_first_not_of("0123456789+-.eE ") == std::string::npos) q.value = r.number(v, ik + ".value", -30, 30);
          else r.fail(v, ik + ".value", e.what());
        }
        if (unit) {
          if (q.unit != Unit::Volt && q.unit != Unit::Milliamp)
            r.fail(v, ik + ".value", "an analog input's value is in V or mA, got '" + text + "'");
          const bool ma = q.unit == Unit::Milliamp;
          if (in[j]["current"] && a.current != ma)
            r.fail(v, ik + ".value", std::string("'") + text + "' on a " + (a.current ? "current (current: true)" : "voltage (current: false)") + " input");
          a.current = ma;
          if (!(q.value >= -30 && q.value <= 30))
            r.fail(v, ik + ".value", "'" + text + "' out of range -30..30 " + unit_name(q.unit));
        }
        a.value = q.value;
      }
      if (in[j]["plant"]) a.plant = r.str(in[j]["plant"], ik + ".plant");
      if (in[j]["offset"]) a.offset = r.boolean(in[j]["offset"], ik + ".offset");
      if (const YAML::Node pr = in[j]["plant_range"]) {
        if (!pr.IsSequence() || pr.size() != 2) r.fail(pr, ik + ".plant_range", "expected [low, high] in degC");
        a.plant_lo = r.number(pr[0], ik + ".plant_range", -273, 3000);
        a.plant_hi = r.number(pr[1], ik + ".plant_range", -273, 3000);
        if (a.plant_hi <= a.plant_lo) r.fail(pr, ik + ".plant_range", "high must exceed low");
      }
      if (const YAML::Node c = in[j]["conditioning"]) a.conditioning = parse_conditioning(r, c, ik + ".conditioning", false);
      ins->push_back(a);
    }
  }
  if (const YAML::Node out = m["outputs"]) {
    if (!out.IsSequence() || int(out.size()) > ao)
      r.fail(out, mk + ".outputs", "a list of at most " + std::to_string(ao) + " outputs for a " + type);
    for (size_t j = 0; j < out.size(); ++j) {
      const std::string ok = mk + ".outputs[" + std::to_string(j) + "]";
      r.only(out[j], ok, {"name", "current", "conditioning"});
      AnalogOutputDef o;
      if (out[j]["name"]) o.name = r.str(out[j]["name"], ok + ".name");
      if (out[j]["current"]) o.current = r.boolean(out[j]["current"], ok + ".current");
      if (const YAML::Node c = out[j]["conditioning"]) o.conditioning = parse_conditioning(r, c, ok + ".conditioning", true);
      outs->push_back(o);
    }
  }
}

}  // namespace

int32_t board_input_code(double signal, bool current) {
  const double frac = std::clamp(signal / (current ? 20.0 : 10.0), 0.0, 1.0);
  return 4 * int32_t(std::floor(frac * 4095 + 0.5));
}

double board_output_signal(int32_t code, bool current) {
  const int32_t c = std::clamp(code, 0, kBoardFullCode) / 4;
  return c / 4095.0 * (current ? 20.0 : 10.0);
}

AnalogConfig parse_analog_config(const YAML::Node& node, const std::string& file) {
  const YamlReader r(file);
  AnalogConfig c;
  const std::string k = "modules.analog";
  r.only(node, k, {"first_ir", "first_or", "modules", "board"});
  if (const YAML::Node b = node["board"]) {
    const std::string bk = k + ".board";
    r.only(b, bk, {"type", "inputs", "outputs"});
    if (!b["type"]) r.fail(b, bk + ".type", "missing");
    c.board.type = r.choice(b["type"], bk + ".type", {"B4AD", "B2DA", "B2A1D"});
    for (const auto& kd : kBoards)
      if (c.board.type == kd.name) parse_channels(file, b, bk, c.board.type, kd.ai, kd.ao, &c.board.inputs, &c.board.outputs);
  }
  if (node["first_ir"]) c.first_ir = uint32_t(r.number(node["first_ir"], k + ".first_ir", 0, 63));
  if (node["first_or"]) c.first_or = uint32_t(r.number(node["first_or"], k + ".first_or", 0, 63));
  const YAML::Node ms = node["modules"];
  if (!ms) return c;
  if (!ms.IsSequence()) r.fail(ms, k + ".modules", "expected a list");
  uint32_t irs = c.first_ir, ors = c.first_or;
  for (size_t i = 0; i < ms.size(); ++i) {
    const std::string mk = k + ".modules[" + std::to_string(i) + "]";
    const YAML::Node m = ms[i];
    r.only(m, mk, {"type", "code", "signal", "span", "inputs", "outputs"});
    AnalogModuleDef d;
    if (!m["type"]) r.fail(m, mk + ".type", "missing");
    d.type = r.choice(m["type"], mk + ".type", {"6AD", "4A2D", "4DA", "2DA", "2A4TC", "2A4RTD"});
    int ai = 0, ao = 0;
    for (const auto& kd : kKinds)
      if (d.type == kd.name) ai = kd.ai, ao = kd.ao;
    if (m["code"]) d.bipolar_code = r.choice(m["code"], mk + ".code", {"unipolar", "bipolar"}) == "bipolar";
    if (m["signal"]) d.bipolar_signal = r.choice(m["signal"], mk + ".signal", {"unipolar", "bipolar"}) == "bipolar";
    if (m["span"]) d.span10 = r.number(m["span"], mk + ".span", 5, 10) == 10;
    if (m["span"] && !d.span10 && r.number(m["span"], mk + ".span", 5, 10) != 5) r.fail(m["span"], mk + ".span", "5 or 10");
    parse_channels(file, m, mk, d.type, ai, ao, &d.inputs, &d.outputs);
    irs += uint32_t(ai);
    ors += uint32_t(ao);
    if (irs > 64) r.fail(m, mk, "more than 64 analog inputs (IR R3840-R3903)");
    if (ors > 64) r.fail(m, mk, "more than 64 analog outputs (OR R3904-R3967)");
    c.modules.push_back(d);
  }
  return c;
}

AnalogModules::AnalogModules(AnalogConfig cfg, Memory& mem, std::function<double(const std::string&)> plant)
    : cfg_(std::move(cfg)), mem_(mem), plant_temperature_(std::move(plant)) {
  uint32_t ir = cfg_.first_ir, orr = cfg_.first_or;
  for (const auto& m : cfg_.modules) {
    int ai = 0, ao = 0;
    for (const auto& kd : kKinds)
      if (m.type == kd.name) ai = kd.ai, ao = kd.ao;
    // Every channel of the module occupies its IR/OR, listed or not (unlisted inputs read 0 V).
    for (int j = 0; j < ai; ++j) {
      Input in;
      if (j < int(m.inputs.size())) in.def = m.inputs[size_t(j)];
      in.conditioning = ConditionedChannel(in.def.conditioning);
      in.ir_index = ir++;
      in.range = AnalogRange{m.bipolar_signal, m.span10, in.def.current};
      in.bipolar_code = m.bipolar_code;
      inputs_.push_back(in);
    }
    for (int j = 0; j < ao; ++j) {
      Output o;
      if (j < int(m.outputs.size())) o.name = m.outputs[size_t(j)].name;
      o.or_index = orr++;
      o.range = AnalogRange{m.bipolar_signal, m.span10, j < int(m.outputs.size()) && m.outputs[size_t(j)].current};
      o.bipolar_code = m.bipolar_code;
      outputs_.push_back(o);
      output_conditioning_.emplace_back(j < int(m.outputs.size()) ? m.outputs[size_t(j)].conditioning : ConditioningDef());
    }
  }
  for (const auto& kd : kBoards) {
    if (cfg_.board.type != kd.name) continue;
    const AnalogBoardDef& b = cfg_.board;
    for (int j = 0; j < kd.ai; ++j) {
      Input in;
      if (j < int(b.inputs.size())) in.def = b.inputs[size_t(j)];
      in.conditioning = ConditionedChannel(in.def.conditioning);
      in.ir_index = uint32_t(j);
      in.board = true;
      in.range = AnalogRange{false, true, in.def.current};  // 0-10 V / 0-20 mA
      in.bipolar_code = false;
      inputs_.push_back(in);
    }
    for (int j = 0; j < kd.ao; ++j) {
      Output o;
      if (j < int(b.outputs.size())) o.name = b.outputs[size_t(j)].name;
      o.or_index = uint32_t(j);
      o.board = true;
      o.range = AnalogRange{false, true, j < int(b.outputs.size()) && b.outputs[size_t(j)].current};
      o.bipolar_code = false;
      outputs_.push_back(o);
      output_conditioning_.emplace_back(j < int(b.outputs.size()) ? b.outputs[size_t(j)].conditioning : ConditioningDef());
    }
  }
}

void AnalogModules::before_inputs(uint64_t now_us) {
  if (serviced_ && now_us - last_service_us_ < kWatchdogUs) return;
  for (auto& o : outputs_) o.signal = 0, o.watchdog = true;  // 0 V / 0 mA
}

void AnalogModules::before_program(uint64_t) {
  const bool twelve = mem_.reg(Area::D, 4042) == 0x5612;
  for (auto& in : inputs_) {
    double x = in.def.value;
    if (!in.def.plant.empty()) {
      const double frac = (plant_temperature_(in.def.plant) - in.def.plant_lo) / (in.def.plant_hi - in.def.plant_lo);
      // A transmitter: 0..full of the range, or 4..20 mA (live zero) with offset.
      x = in.def.offset ? 4.0 + 16.0 * frac : in.range.lo() + frac * (in.range.hi() - in.range.lo());
    }
    if (in.board) {  // no formats, no averaging: the board's 12 bits every scan
      int32_t code = board_input_code(x, in.def.current);
      // Conditioning counts are the board's 12-bit steps (0..4095), shown x 4.
      if (in.conditioning.enabled()) code = 4 * in.conditioning.sample(code / 4, 0, kBoardFullCode / 4);
      mem_.set_reg(Area::D, kBoardFirstIn + in.ir_index, uint16_t(code));
      continue;
    }
    const int32_t code = ai_code14(in.range, x, in.bipolar_code);
    const uint32_t n = in.ir_index;
    const bool valid14 = !twelve && (mem_.reg(Area::D, 4006 + n / 16) >> (n % 16) & 1u);
    // D4010 + n/2: low byte even channels, high byte odd; illegal -> 1 (valid 12) or 8 (valid 14).
    const uint16_t avg_reg = mem_.reg(Area::D, 4010 + n / 2);
    uint32_t avg = n % 2 ? avg_reg >> 8 : avg_reg & 0xFF;
    if (avg < 1 || avg > 16) avg = valid14 ? 8 : 1;
    // Moving average over the last avg per-scan samples.
    in.window[in.next] = code;
    in.next = (in.next + 1) % 16;
    in.count = std::min<uint32_t>(in.count + 1, 16);
    const uint32_t k = std::min(avg, in.count);
    int64_t sum = 0;
    for (uint32_t s = 0; s < k; ++s) sum += in.window[(in.next + 16 - 1 - s) % 16];
    int32_t mean = int32_t(std::floor(double(sum) / k + 0.5));
    // The conditioning takes what the module delivers this scan, in 14-bit counts,
    // before the register format.
    if (in.conditioning.enabled())
      mean = in.bipolar_code ? in.conditioning.sample(mean, -8192, 8191) : in.conditioning.sample(mean, 0, 16383);
    const AiFormat f = twelve ? AiFormat::Bits12 : valid14 ? AiFormat::Valid14 : AiFormat::Valid12In14;
    mem_.set_reg(Area::R, 3840 + n, uint16_t(int16_t(ai_register(mean, f))));
  }
}

void AnalogModules::after_program(uint64_t now_us) {
  serviced_ = true;
  last_service_us_ = now_us;
  for (size_t i = 0; i < outputs_.size(); ++i) {
    Output& o = outputs_[i];
    const ConditionedChannel& c = output_conditioning_[i];
    if (o.board) {
      int32_t code = int16_t(mem_.reg(Area::D, kBoardFirstOut + o.or_index));
      // Conditioning counts are the board's 12-bit steps: the code as the DAC takes it.
      if (c.enabled()) code = 4 * c.output(std::clamp(code, 0, kBoardFullCode) / 4, 0, kBoardFullCode / 4);
      o.signal = board_output_signal(code, o.range.current);
    } else {
      int32_t code = int16_t(mem_.reg(Area::R, 3904 + o.or_index));
      // In 14-bit counts, on the code clamped to its range as the module takes it.
      const int32_t lo = o.bipolar_code ? -8192 : 0, hi = o.bipolar_code ? 8191 : 16383;
      if (c.enabled()) code = c.output(std::clamp(code, lo, hi), lo, hi);
      o.signal = ao_signal(o.range, code, o.bipolar_code);
    }
    o.watchdog = false;
  }
}

bool AnalogModules::drive_input(const std::string& name, double signal, bool current, std::string* why) {
  for (auto& in : inputs_) {
    if (in.def.name != name) continue;
    if (in.def.current != current) {
      *why = "analog input '" + name + "' is a " + (in.def.current ? "current (mA)" : "voltage (V)") + " input";
      return false;
    }
    in.def.value = signal;
    in.def.plant.clear();
    return true;
  }
  *why = "no analog input named '" + name + "' in modules.analog";
  return false;
}

}  // namespace temp
}  // namespace plc_cell
