#include "plc_cell/recording/recorder.h"

#include <zlib.h>

#include <cstring>

#include "codec.h"
#include "plc_cell/recording/envelope.h"

namespace plc_cell {
namespace recording {

namespace {

// The indexes where a and b differ: blocks compared whole first, as most of memory
// does not change from one scan to the next.
template <typename T>
void diff(const std::vector<T>& a, const std::vector<T>& b, std::vector<uint32_t>* out) {
  constexpr size_t kBlock = 512 / sizeof(T);
  out->clear();
  for (size_t at = 0; at < a.size(); at += kBlock) {
    const size_t n = std::min(kBlock, a.size() - at);
    if (std::memcmp(&a[at], &b[at], n * sizeof(T)) == 0) continue;
    for (size_t i = at; i < at + n; ++i)
      if (a[i] != b[i]) out->push_back(uint32_t(i));
  }
}

void write_info(const RecordingInfo& info, ByteWriter& w) {
  w.string(info.source);
  w.string(info.program_file);
  w.string(info.program_text);
  w.varint(info.signals.size());
  for (const auto& s : info.signals) {
    w.string(s.first);
    w.u8(uint8_t(s.second.area));
    w.u8(uint8_t(s.second.width));
    w.varint(s.second.index);
  }
  w.varint(info.scan_period_us);
  w.u8(info.failure_us ? 1 : 0);
  if (info.failure_us) {
    w.varint(*info.failure_us);
    w.string(info.failure);
  }
}

}  // namespace

Recorder::Recorder(RecordingInfo info) : info_(std::move(info)) {}

void Recorder::start(const Plc& plc) {
  initial_mode_ = plc.locked([&](const ScanEngine& e, const Memory& m) {
    capture(m, &initial_);
    return uint8_t(e.mode());
  });
  prev_ = initial_;
  started_ = true;
}

void Recorder::scanned(const Plc& plc, uint64_t t_us) {
  if (!started_) start(plc);
  const uint8_t mode = plc.locked([&](const ScanEngine& e, const Memory& m) {
    capture(m, &cur_);
    return uint8_t(e.mode());
  });
  ByteWriter w;
  w.varint(t_us - (scans_ ? last_t_ : 0));
  w.u8(mode);
  std::vector<uint32_t> changed;
  diff(prev_.bits, cur_.bits, &changed);
  w.varint(changed.size());
  for (size_t i = 0; i < changed.size(); ++i) {
    w.varint(i ? changed[i] - changed[i - 1] - 1 : changed[i]);
    w.u8(cur_.bits[changed[i]]);
  }
  diff(prev_.words, cur_.words, &changed);
  w.varint(changed.size());
  for (size_t i = 0; i < changed.size(); ++i) {
    w.varint(i ? changed[i] - changed[i - 1] - 1 : changed[i]);
    w.varint(cur_.words[changed[i]]);
  }
  scans_bytes_ += w.bytes();
  std::swap(prev_, cur_);
  last_t_ = t_us;
  ++scans_;
}

void Recorder::set_failure(uint64_t t_us, const std::string& text) {
  info_.failure_us = t_us;
  info_.failure = text;
}

std::string Recorder::bytes() const { return pack(payload(), kFormatVersion); }

std::string Recorder::payload() const {
  ByteWriter w;
  write_info(info_, w);
  w.varint(initial_.bits.size());
  w.varint(initial_.words.size());
  w.raw(initial_.bits.data(), initial_.bits.size());
  for (uint16_t v : initial_.words) w.u16(v);
  w.u8(initial_mode_);
  w.varint(scans_);
  w.bytes() += scans_bytes_;
  return w.bytes();
}

void Recorder::save(const std::string& path) const { write_recording_file(path, bytes()); }

}  // namespace recording
}  // namespace plc_cell
