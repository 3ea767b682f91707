#include "plc_cell/tri/memory_map.h"

namespace plc_cell {
namespace tri {
namespace {

Address reg(Area a, uint32_t i, Width w = Width::Word) { return Address{a, w, i}; }

bool in(uint32_t n, uint32_t hi) { return n >= 1 && n <= hi; }

}  // namespace

uint32_t bit_count(BitKind k) {
  switch (k) {
    case BitKind::Input:
    case BitKind::Output: return kIoPoints;
    case BitKind::Relay: return kRelays;
    case BitKind::Timer: return kTimers;
    case BitKind::Counter: return kCounters;
  }
  return 0;
}

bool bit_address(BitKind k, uint32_t n, Address* out) {
  if (!in(n, bit_count(k))) return false;
  static const Area kArea[] = {Area::X, Area::Y, Area::M, Area::T, Area::C};
  *out = reg(kArea[int(k)], k == BitKind::Timer ? kFirstTimer + n - 1 : n - 1, Width::Bit);
  return true;
}

Address timer_pv(uint32_t n) { return reg(Area::RT, kFirstTimer + n - 1); }
Address timer_sv(uint32_t n) { return reg(Area::R, kTimerSvR + n - 1); }
Address counter_pv(uint32_t n) { return reg(Area::RC, n - 1); }
Address counter_sv(uint32_t n) { return reg(Area::R, kCounterSvR + n - 1); }

bool integer_var(uint32_t k, Address* out) {
  if (k > 25) return false;
  *out = reg(Area::R, kIntegersR + 2 * k, Width::DWord);
  return true;
}

bool dm(uint32_t n, Address* out) {
  if (!in(n, kDmWords)) return false;
  *out = reg(Area::D, n - 1);
  return true;
}

bool hsc_pv(uint32_t n, Address* out) {
  if (!in(n, kHsc)) return false;
  *out = reg(Area::R, kHscCvR + 4 * (n - 1), Width::DWord);
  return true;
}

bool adc(uint32_t n, Address* out) {
  if (!in(n, kAdcChannels)) return false;
  *out = reg(Area::R, kAdcR + n - 1);
  return true;
}

bool dac(uint32_t n, Address* out) {
  if (!in(n, kDacChannels)) return false;
  *out = reg(Area::R, kDacR + n - 1);
  return true;
}

bool pwm(uint32_t n, Address* out) {
  if (!in(n, kPwmChannels)) return false;
  *out = reg(Area::R, kPwmR + n - 1);
  return true;
}

bool eeprom_int(uint32_t a, Address* out) {
  if (!in(a, kEepromInts)) return false;
  *out = reg(Area::F, kEepromF + a - 1);
  return true;
}

bool string_var(uint32_t k, Address* first) {
  if (k > 25) return false;
  *first = reg(Area::F, kStringsF + kStringWords * k);
  return true;
}

bool eeprom_string(uint32_t s, Address* first) {
  if (!in(s, kEepromStrings)) return false;
  *first = reg(Area::F, kEepromStringF + (kEepromStringChars / 2) * (s - 1));
  return true;
}

bool time_register(uint32_t i, Address* out) {
  if (!in(i, 3)) return false;
  *out = reg(Area::R, 4131 - i);  // hour R4130, minute R4129, second R4128
  return true;
}

bool date_register(uint32_t i, Address* out) {
  static const uint32_t kReg[] = {4133, 4132, 4131, 4134};
  if (!in(i, 4)) return false;
  *out = reg(Area::R, kReg[i - 1]);
  return true;
}

uint16_t date_from_fbs(uint32_t i, uint16_t v) {
  if (i == 1) return uint16_t(2000 + v % 100);
  if (i == 4) return v == 0 ? 7 : v;
  return v;
}

uint16_t date_to_fbs(uint32_t i, uint16_t v) {
  if (i == 1) return uint16_t(v % 100);
  if (i == 4) return v == 7 ? 0 : v;
  return v;
}

}  // namespace tri
}  // namespace plc_cell
