#pragma once
// Where the TRi FMD1616-10's data elements live in the soft PLC's FBs memory: the one
// place of the mapping (docs/tri.md, "Memory map"). TRi numbers are 1-based as in TBASIC
// (INPUT 1 = X0); a function returns false for a number the TRi does not have.
#include <cstdint>

#include "plc_cell/core/address.h"

namespace plc_cell {
namespace tri {

constexpr uint32_t kIoPoints = 256;      // inputs, outputs 1..256
constexpr uint32_t kRelays = 512;        // relays 1..512
constexpr uint32_t kTimers = 64;         // timers 1..64 (0.1 s)
constexpr uint32_t kCounters = 64;       // counters 1..64
constexpr uint32_t kDmWords = 4000;      // DM[1..4000]
constexpr uint32_t kHsc = 2;             // HSCPV[1..2]
constexpr uint32_t kAdcChannels = 8;     // ADC 1..8
constexpr uint32_t kDacChannels = 4;     // DAC 1..4 (2 on board, 2 on the I2C-FRTC)
constexpr uint32_t kPwmChannels = 4;     // PWM 1..4
constexpr uint32_t kEepromInts = 4000;   // EEPROM integers 1..4000
constexpr uint32_t kEepromStrings = 150; // EEPROM strings 1..150, 40 characters
constexpr uint32_t kEepromStringChars = 40;
constexpr uint32_t kStringChars = 70;    // A$..Z$

// The FBs registers behind the elements with no FBs counterpart of their own.
constexpr uint32_t kTimerSvR = 3600;     // timer n's SV: R(3599+n), R3600..R3663
constexpr uint32_t kCounterSvR = 3664;   // counter n's SV: R(3663+n), R3664..R3727
constexpr uint32_t kIntegersR = 3760;    // A..Z: DR3760, DR3762, ... DR3810 (low word first)
constexpr uint32_t kFirstTimer = 50;     // timer n: T(49+n), RT(49+n) (T50..T199 are 0.1 s)
constexpr uint32_t kAdcR = 3840;         // ADC n: R(3839+n), the FBs analog inputs
constexpr uint32_t kDacR = 3904;         // DAC n: R(3903+n), the FBs analog outputs
constexpr uint32_t kPwmR = 3812;         // PWM n: R(3811+n), the duty of the last SETPWM (0.01 %)
constexpr uint32_t kHscCvR = 4096;       // HSCPV[n]: DR(4096+4(n-1)), the CV of HSC0, HSC1
constexpr uint32_t kEepromF = 0;         // EEPROM integer a: F(a-1), F0..F3999
constexpr uint32_t kEepromStringF = 4000;// EEPROM string s: F(4000+20(s-1)), 20 words each
constexpr uint32_t kStringsF = 7000;     // A$..Z$: F(7000+35k), 35 words each
constexpr uint32_t kStringWords = 35;

// One discrete: INPUT n -> X(n-1), OUTPUT n -> Y(n-1), RELAY n -> M(n-1),
// TIMER n -> T(49+n), COUNTER n -> C(n-1).
enum class BitKind : uint8_t { Input, Output, Relay, Timer, Counter };
bool bit_address(BitKind k, uint32_t n, Address* out);
uint32_t bit_count(BitKind k);  // 256, 256, 512, 64, 64

Address timer_pv(uint32_t n);    // RT(49+n)
Address timer_sv(uint32_t n);    // R(3599+n)
Address counter_pv(uint32_t n);  // RC(n-1)
Address counter_sv(uint32_t n);  // R(3663+n)
bool integer_var(uint32_t k, Address* out);   // k 0..25 (A..Z) -> DR(3760+2k)
bool dm(uint32_t n, Address* out);            // DM[n], 1..4000 -> D(n-1)
bool hsc_pv(uint32_t n, Address* out);        // 1..2 -> DR4096, DR4100
bool adc(uint32_t n, Address* out);           // 1..8 -> R3840..R3847
bool dac(uint32_t n, Address* out);           // 1..4 -> R3904..R3907
bool pwm(uint32_t n, Address* out);           // 1..4 -> R3812..R3815
bool eeprom_int(uint32_t a, Address* out);    // 1..4000 -> F0..F3999
// String storage: first word and words; 2 characters a word, high byte first, ending at
// the first NUL (or filling every word).
bool string_var(uint32_t k, Address* first);     // k 0..25 (A$..Z$)
bool eeprom_string(uint32_t s, Address* first);  // 1..150

// TIME[1..3] (hour, minute, second) and DATE[1..4] (year, month, day, day of week
// 1 = Monday .. 7 = Sunday) on the FBs RTC registers R4128..R4134 (binary; year 0-99
// for 2000-2099, day of week 0 = Sunday). Conversions both ways.
bool time_register(uint32_t i, Address* out);   // 1 -> R4130, 2 -> R4129, 3 -> R4128
bool date_register(uint32_t i, Address* out);   // 1 -> R4133, 2 -> R4132, 3 -> R4131, 4 -> R4134
uint16_t date_from_fbs(uint32_t i, uint16_t reg);  // year +2000, week 0 -> 7
uint16_t date_to_fbs(uint32_t i, uint16_t value);  // year -2000 (mod 100), week 7 -> 0

}  // namespace tri
}  // namespace plc_cell
