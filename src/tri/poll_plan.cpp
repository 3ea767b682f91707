#include "plc_cell/tri/poll_plan.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>
#include <set>

#include "plc_cell/core/error.h"
#include "plc_cell/tri/memory_map.h"

namespace plc_cell {
namespace tri {
namespace {

// The discretes of a TRi: where TRi number 1 sits in the FBs area, how many, the RVS/WVS
// type of their words of 16 and their wb base.
struct BitSpace {
  Area area;
  uint32_t first, count, rvs_type, wb_base;
  const char* name;
};
const BitSpace kBits[] = {
    {Area::X, 0, kIoPoints, 1, 0x000, "inputs X0-X255"},
    {Area::Y, 0, kIoPoints, 2, 0x100, "outputs Y0-Y255"},
    {Area::M, 0, kRelays, 3, 0x400, "relays M0-M511"},
    {Area::T, kFirstTimer, kTimers, 4, 0x200, "timer contacts T50-T113"},
    {Area::C, 0, kCounters, 5, 0x300, "counter contacts C0-C63"},
};

const BitSpace* bit_space(Area a) {
  for (const auto& b : kBits)
    if (b.area == a) return &b;
  return nullptr;
}

uint32_t width_bits(const Address& a) { return a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32; }

Request req(Cmd c, uint32_t a = 0, uint32_t b = 0) {
  Request r;
  r.cmd = c;
  r.a = a;
  r.b = b;
  return r;
}

// What one element needs: single requests, or a place in an ADC / EEPROM run.
struct Need {
  enum Kind { Single, Adc, Eeprom } kind = Single;
  Request request;
  uint32_t n = 0;  // ADC channel, EEPROM address
  int shift = 0;
};
struct Spec {
  std::vector<Need> needs;
  uint32_t mask = 0xFFFF;
};

[[noreturn]] void not_on_tri(const Address& a) {
  throw Error(format_address(a) +
              " is not on a TRi: it has X0-X255, Y0-Y255, M0-M511, T50-T113, C0-C63 (and their W/DW words), "
              "RT50-RT113, RC0-RC63, R3600-R3727 (SVs), DR3760-DR3810 (A-Z), R3812-R3815 (PWM), R3840-R3847 (ADC), "
              "R3904-R3907 (DAC), "
              "DR4096, DR4100 (HSCPV), D0-D3999 (DM), F0-F3999 (EEPROM) (docs/tri.md, tri_bridge)");
}

bool in(uint32_t i, uint32_t lo, uint32_t n) { return i >= lo && i < lo + n; }

// A 32-bit variable (A-Z, HSCPV) read whole, or one of its words.
Spec var32(const Address& a, Cmd cmd, uint32_t which, uint32_t half) {
  Spec s;
  if (a.width == Width::DWord) {
    if (half != 0) not_on_tri(a);
    s.mask = 0xFFFFFFFF;
    s.needs.push_back({Need::Single, req(cmd, which), 0, 0});
  } else {
    s.needs.push_back({Need::Single, req(cmd, which), 0, -int(16 * half)});
  }
  return s;
}

Spec classify(const Address& a) {
  Spec s;
  if (const BitSpace* b = bit_space(a.area)) {
    const uint32_t w = width_bits(a);
    if (a.index < b->first || a.index - b->first + w > b->count) not_on_tri(a);
    const uint32_t p0 = a.index - b->first;
    s.mask = w == 32 ? 0xFFFFFFFF : (1u << w) - 1;
    for (uint32_t k = p0 / 16; k <= (p0 + w - 1) / 16; ++k)
      s.needs.push_back({Need::Single, req(Cmd::ReadSystem, b->rvs_type, k + 1), 0, int(16 * k) - int(p0)});
    return s;
  }
  const uint32_t i = a.index;
  const bool word = a.width == Width::Word;
  switch (a.area) {
    case Area::RT:
      if (!word || !in(i, kFirstTimer, kTimers)) not_on_tri(a);
      s.needs.push_back({Need::Single, req(Cmd::ReadSystem, 6, i - kFirstTimer + 1)});
      return s;
    case Area::RC:
      if (!word || i >= kCounters) not_on_tri(a);
      s.needs.push_back({Need::Single, req(Cmd::ReadSystem, 7, i + 1)});
      return s;
    case Area::D:
      if (word && i < kDmWords) {
        s.needs.push_back({Need::Single, req(Cmd::ReadDm, i + 1)});
        return s;
      }
      if (a.width == Width::DWord && i + 1 < kDmWords) {  // low word at the lower address
        s.mask = 0xFFFFFFFF;
        s.needs.push_back({Need::Single, req(Cmd::ReadDm, i + 1), 0, 0});
        s.needs.push_back({Need::Single, req(Cmd::ReadDm, i + 2), 0, 16});
        return s;
      }
      not_on_tri(a);
    case Area::F:
      if (!word || i >= kEepromInts) not_on_tri(a);
      s.needs.push_back({Need::Eeprom, {}, i + 1});
      return s;
    case Area::R:
      if (a.width != Width::Bit) {
        if (in(i, kIntegersR, 52)) return var32(a, Cmd::ReadInteger, (i - kIntegersR) / 2, (i - kIntegersR) % 2);
        if (in(i, kHscCvR, 2)) return var32(a, Cmd::ReadHsc, 1, i - kHscCvR);
        if (in(i, kHscCvR + 4, 2)) return var32(a, Cmd::ReadHsc, 2, i - kHscCvR - 4);
      }
      if (!word) not_on_tri(a);
      if (in(i, kTimerSvR, kTimers)) s.needs.push_back({Need::Single, req(Cmd::ReadTimerSv, i - kTimerSvR)});
      else if (in(i, kCounterSvR, kCounters)) s.needs.push_back({Need::Single, req(Cmd::ReadCounterSv, i - kCounterSvR)});
      else if (in(i, kAdcR, kAdcChannels)) s.needs.push_back({Need::Adc, {}, i - kAdcR + 1});
      else if (in(i, kDacR, kDacChannels)) s.needs.push_back({Need::Single, req(Cmd::ReadSystem, 0x0C, i - kDacR + 1)});
      else if (in(i, kPwmR, kPwmChannels)) s.needs.push_back({Need::Single, req(Cmd::ReadSystem, 0x0D, i - kPwmR + 1)});
      else not_on_tri(a);
      return s;
    default:
      not_on_tri(a);
  }
}

// Runs over the sorted numbers (read through gaps of up to kMaxGap, at most max each);
// *where maps a number to (request, field).
void runs(const std::set<uint32_t>& ns, Cmd cmd, uint32_t max, std::vector<Request>* requests,
          std::map<uint32_t, std::pair<uint32_t, uint32_t>>* where) {
  auto it = ns.begin();
  while (it != ns.end()) {
    const uint32_t first = *it;
    uint32_t last = first;
    auto next = std::next(it);
    while (next != ns.end() && *next - last <= kMaxGap + 1 && *next - first < max) last = *next++;
    const uint32_t r = uint32_t(requests->size());
    requests->push_back(req(cmd, first, last - first + 1));
    for (; it != next; ++it) (*where)[*it] = {r, *it - first};
  }
}

uint32_t parse_index(const std::string& text, size_t open, uint32_t hi) {
  const size_t close = text.find(']', open);
  if (close == std::string::npos || close != text.size() - 1) throw Error("'" + text + "': expected NAME[n]");
  const std::string n = text.substr(open + 1, close - open - 1);
  char* end = nullptr;
  const long v = std::strtol(n.c_str(), &end, 10);
  if (n.empty() || *end || v < 1 || v > long(hi))
    throw Error("'" + text + "': index must be 1-" + std::to_string(hi));
  return uint32_t(v);
}

Address at(Area area, uint32_t index, Width w = Width::Word) { return Address{area, w, index}; }

}  // namespace

Address parse_point(const std::string& text) {
  std::string up;
  for (char c : text) up += char(std::toupper(static_cast<unsigned char>(c)));
  if (up.size() == 1 && up[0] >= 'A' && up[0] <= 'Z') return at(Area::R, kIntegersR + 2 * uint32_t(up[0] - 'A'), Width::DWord);
  const size_t open = up.find('[');
  if (open != std::string::npos) {
    const std::string name = up.substr(0, open);
    struct Named {
      const char* name;
      uint32_t hi;
      Address (*make)(uint32_t n);
    };
    static const Named kNamed[] = {
        {"INPUT", 16, [](uint32_t n) { return at(Area::X, 16 * (n - 1)); }},
        {"OUTPUT", 16, [](uint32_t n) { return at(Area::Y, 16 * (n - 1)); }},
        {"RELAY", 32, [](uint32_t n) { return at(Area::M, 16 * (n - 1)); }},
        {"TIMERBIT", 4, [](uint32_t n) { return at(Area::T, kFirstTimer + 16 * (n - 1)); }},
        {"CTRBIT", 4, [](uint32_t n) { return at(Area::C, 16 * (n - 1)); }},
        {"TIMERPV", kTimers, [](uint32_t n) { return timer_pv(n); }},
        {"TIMERSV", kTimers, [](uint32_t n) { return timer_sv(n); }},
        {"CTRPV", kCounters, [](uint32_t n) { return counter_pv(n); }},
        {"CTRSV", kCounters, [](uint32_t n) { return counter_sv(n); }},
        {"DM", kDmWords, [](uint32_t n) { return at(Area::D, n - 1); }},
        {"HSCPV", kHsc, [](uint32_t n) { return at(Area::R, kHscCvR + 4 * (n - 1), Width::DWord); }},
        {"ADC", kAdcChannels, [](uint32_t n) { return at(Area::R, kAdcR + n - 1); }},
        {"DAC", kDacChannels, [](uint32_t n) { return at(Area::R, kDacR + n - 1); }},
        {"PWM", kPwmChannels, [](uint32_t n) { return at(Area::R, kPwmR + n - 1); }},
        {"EEPROM", kEepromInts, [](uint32_t n) { return at(Area::F, n - 1); }},
    };
    for (const auto& k : kNamed)
      if (name == k.name) return k.make(parse_index(up, open, k.hi));
    throw Error("'" + text + "': no TRi element " + name +
                "[] (INPUT, OUTPUT, RELAY, TIMERBIT, CTRBIT, TIMERPV, TIMERSV, CTRPV, CTRSV, DM, HSCPV, ADC, DAC, PWM, "
                "EEPROM)");
  }
  const Address a = parse_address(text);
  check_on_tri(a, 1);
  return a;
}

void check_on_tri(const Address& start, uint32_t count) {
  check_span(start, count);
  for (uint32_t k = 0; k < count; ++k) classify(offset_address(start, k));
}

PollPlan plan_poll(const std::vector<PollItem>& items) {
  std::vector<std::vector<Spec>> specs;
  std::set<uint32_t> adcs, eeproms;
  for (const auto& it : items) {
    check_span(it.start, it.count);
    specs.emplace_back();
    for (uint32_t k = 0; k < it.count; ++k) {
      specs.back().push_back(classify(offset_address(it.start, k)));
      for (const Need& n : specs.back().back().needs) {
        if (n.kind == Need::Adc) adcs.insert(n.n);
        if (n.kind == Need::Eeprom) eeproms.insert(n.n);
      }
    }
  }
  PollPlan plan;
  std::map<std::string, uint32_t> single;  // the same frame is sent once
  std::map<uint32_t, std::pair<uint32_t, uint32_t>> adc_at, eeprom_at;
  runs(adcs, Cmd::ReadAnalog, kAdcChannels, &plan.requests, &adc_at);
  runs(eeproms, Cmd::ReadEepromInts, kMaxRxi, &plan.requests, &eeprom_at);
  for (const auto& item : specs) {
    plan.items.emplace_back();
    for (const Spec& s : item) {
      PollPlan::Element e;
      e.mask = s.mask;
      for (const Need& n : s.needs) {
        PollPlan::Part p;
        p.shift = n.shift;
        if (n.kind == Need::Adc) {
          p.request = adc_at[n.n].first;
          p.field = adc_at[n.n].second;
        } else if (n.kind == Need::Eeprom) {
          p.request = eeprom_at[n.n].first;
          p.field = eeprom_at[n.n].second;
        } else {
          const auto ins = single.emplace(encode_request(n.request), uint32_t(plan.requests.size()));
          if (ins.second) plan.requests.push_back(n.request);
          p.request = ins.first->second;
        }
        e.parts.push_back(p);
      }
      plan.items.back().push_back(e);
    }
  }
  return plan;
}

std::vector<std::vector<uint32_t>> run_poll(Client& c, const PollPlan& plan) {
  std::vector<Response> rsp;
  rsp.reserve(plan.requests.size());
  for (const Request& r : plan.requests) {
    rsp.push_back(c.transact(r));
    if (rsp.back().values.size() < (r.cmd == Cmd::ReadAnalog || r.cmd == Cmd::ReadEepromInts ? r.b : 1))
      throw CommError("short answer to " + encode_request(r));
  }
  std::vector<std::vector<uint32_t>> out;
  for (const auto& item : plan.items) {
    out.emplace_back();
    for (const auto& e : item) {
      uint64_t v = 0;
      for (const auto& p : e.parts) {
        const uint64_t x = rsp[p.request].values[p.field];
        v |= p.shift >= 0 ? x << p.shift : x >> -p.shift;
      }
      out.back().push_back(uint32_t(v & e.mask));
    }
  }
  return out;
}

uint32_t wb_address(const Address& bit) {
  const BitSpace* b = bit_space(bit.area);
  if (!b || bit.width != Width::Bit || bit.index < b->first || bit.index - b->first >= b->count) not_on_tri(bit);
  return b->wb_base + bit.index - b->first;
}

std::vector<Request> plan_write(const Address& start, const std::vector<uint32_t>& raw) {
  check_on_tri(start, uint32_t(raw.size()));
  std::vector<Request> out;
  auto add = [&](Cmd c, uint32_t a, uint32_t b, std::vector<uint32_t> values) {
    Request r = req(c, a, b);
    r.values = std::move(values);
    out.push_back(std::move(r));
  };
  for (size_t k = 0; k < raw.size(); ++k) {
    const Address a = offset_address(start, uint32_t(k));
    const uint32_t v = raw[k], i = a.index;
    if (const BitSpace* b = bit_space(a.area)) {
      const uint32_t p0 = i - b->first, w = width_bits(a);
      if (w == 1) {
        add(Cmd::ForceBit, wb_address(a), 0, {v & 1});
      } else if (p0 % 16 == 0) {  // whole TRi words: one WVS each
        for (uint32_t j = 0; j < w / 16; ++j) add(Cmd::WriteSystem, b->rvs_type, p0 / 16 + j + 1, {(v >> (16 * j)) & 0xFFFF});
      } else {
        for (uint32_t j = 0; j < w; ++j) add(Cmd::ForceBit, b->wb_base + p0 + j, 0, {(v >> j) & 1});
      }
      continue;
    }
    const bool dword = a.width == Width::DWord;
    switch (a.area) {
      case Area::RT: add(Cmd::WriteSystem, 6, i - kFirstTimer + 1, {v & 0xFFFF}); continue;
      case Area::RC: add(Cmd::WriteSystem, 7, i + 1, {v & 0xFFFF}); continue;
      case Area::D:
        add(Cmd::WriteDm, i + 1, 0, {v & 0xFFFF});
        if (dword) add(Cmd::WriteDm, i + 2, 0, {v >> 16});
        continue;
      case Area::F: {
        // Consecutive EEPROM words: one WXI of up to 16.
        if (!out.empty() && out.back().cmd == Cmd::WriteEepromInts && out.back().a + out.back().b == i + 1 &&
            out.back().b < kMaxWxi) {
          out.back().values.push_back(v & 0xFFFF);
          ++out.back().b;
        } else {
          add(Cmd::WriteEepromInts, i + 1, 1, {v & 0xFFFF});
        }
        continue;
      }
      default: break;
    }
    // R: SVs, A-Z, HSCPV, ADC, DAC.
    if (in(i, kIntegersR, 52) || in(i, kHscCvR, 2) || in(i, kHscCvR + 4, 2)) {
      if (!dword)
        throw Error(format_address(a) + " is half of a 32-bit TRi variable: write it whole (" +
                    (in(i, kIntegersR, 52) ? "DR3760 = A" : "DR4096 = HSCPV[1]") + ")");
      if (in(i, kIntegersR, 52)) add(Cmd::WriteInteger, (i - kIntegersR) / 2, 0, {v});
      else add(Cmd::WriteHsc, i == kHscCvR ? 1 : 2, 0, {v});
    } else if (in(i, kTimerSvR, kTimers) || in(i, kCounterSvR, kCounters)) {
      if (v > 9999) throw Error(format_address(a) + ": a TRi set value is 0-9999");
      if (in(i, kTimerSvR, kTimers)) add(Cmd::WriteTimerSv, i - kTimerSvR, 0, {v});
      else add(Cmd::WriteCounterSv, i - kCounterSvR, 0, {v});
    } else if (in(i, kDacR, kDacChannels)) {
      add(Cmd::WriteSystem, 0x0C, i - kDacR + 1, {v & 0xFFFF});
    } else if (in(i, kPwmR, kPwmChannels)) {
      add(Cmd::WriteSystem, 0x0D, i - kPwmR + 1, {v & 0xFFFF});
    } else {
      throw Error(format_address(a) + " (ADC) is an analog input: it cannot be written");
    }
  }
  return out;
}

}  // namespace tri
}  // namespace plc_cell
