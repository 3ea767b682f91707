#include "plc_cell/recording/reader.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "codec.h"
#include "plc_cell/recording/envelope.h"

namespace plc_cell {
namespace recording {

namespace {

constexpr size_t kMaxText = size_t(64) << 20;
constexpr uint64_t kMaxSignals = 65536;

RunMode read_mode(ByteReader& r, const char* what) {
  const uint8_t m = r.u8(what);
  if (m > uint8_t(RunMode::Run)) r.fail(std::string(what) + " " + std::to_string(m) + " is not STOP (0) or RUN (1)");
  return RunMode(m);
}

Address read_address(ByteReader& r) {
  Address a;
  const uint8_t area = r.u8("signal area");
  if (area >= kAreaCount) r.fail("signal area " + std::to_string(area) + " is not an area");
  const uint8_t width = r.u8("signal width");
  if (width > uint8_t(Width::DWord)) r.fail("signal width " + std::to_string(width) + " is not a width");
  a.area = Area(area);
  a.width = Width(width);
  a.index = uint32_t(r.bounded("signal index", area_size(a.area) - 1));
  return a;
}

void read_info(ByteReader& r, RecordingInfo* info) {
  info->source = r.string("source", kMaxText);
  info->program_file = r.string("program file name", kMaxText);
  info->program_text = r.string("program text", kMaxText);
  const uint64_t n = r.bounded("signal count", kMaxSignals);
  for (uint64_t i = 0; i < n; ++i) {
    std::string name = r.string("signal name", 4096);
    info->signals.emplace_back(std::move(name), read_address(r));
  }
  info->scan_period_us = r.varint("scan period");
  const uint8_t failed = r.u8("failure flag");
  if (failed > 1) r.fail("failure flag " + std::to_string(failed) + " is not 0 or 1");
  if (failed) {
    info->failure_us = r.varint("failure instant");
    info->failure = r.string("failure text", kMaxText);
  }
}

void read_image(ByteReader& r, Image* img) {
  const uint64_t bits = r.varint("bit cell count");
  if (bits != bit_cells())
    r.fail("bit cell count " + std::to_string(bits) + ", this plc_cell has " + std::to_string(bit_cells()));
  const uint64_t words = r.varint("word cell count");
  if (words != word_cells())
    r.fail("word cell count " + std::to_string(words) + ", this plc_cell has " + std::to_string(word_cells()));
  img->bits.resize(bits);
  r.raw(img->bits.data(), bits, "initial bits");
  img->words.resize(words);
  for (auto& w : img->words) w = r.u16("initial words");
}

}  // namespace

Reader Reader::load(const std::string& path) { return parse(read_recording_file(path), path); }

Reader Reader::parse(const std::string& bytes, const std::string& name) {
  return parse_payload(unpack(bytes, name, kFormatVersion), name);
}

Reader Reader::parse_payload(const std::string& payload, const std::string& name) {
  Reader out;
  ByteReader r(payload);
  try {
    read_info(r, &out.info_);
    out.keyframes_.emplace_back();
    out.key_scans_.push_back(0);
    read_image(r, &out.keyframes_.back());
    out.initial_mode_ = read_mode(r, "initial mode");
    out.read_body(r);
    if (r.left()) r.fail(std::to_string(r.left()) + " bytes after the last scan");
  } catch (const FormatError& e) {
    throw RecordingError(name + ": offset " + std::to_string(e.offset) + " of the unpacked data: " + e.what());
  }
  return out;
}

void Reader::read_body(ByteReader& r) {
  // Each scan takes at least 4 bytes: a count larger than the rest could hold is damage.
  const uint64_t n = r.bounded("scan count", r.left() / 4);
  scans_.reserve(n);
  uint64_t t = 0;
  Image img = keyframes_.front();
  for (uint64_t i = 0; i < n; ++i) {
    const std::string at = "scan " + std::to_string(i);
    const uint64_t dt = r.varint("scan instant");
    if (i && dt == 0) r.fail(at + ": instant not after the previous scan's");
    if (t + dt < t) r.fail(at + ": instant past 2^64 us");
    t += dt;
    Scan s{t, read_mode(r, "scan mode"), changes_.size(), 0};
    for (int words = 0; words < 2; ++words) {
      const uint64_t cells = words ? img.words.size() : img.bits.size();
      const uint64_t count = r.bounded(words ? "word change count" : "bit change count", cells);
      uint64_t cell = 0;
      for (uint64_t k = 0; k < count; ++k) {
        cell += r.varint("change index") + (k ? 1 : 0);
        if (cell >= cells) r.fail(at + ": change index " + std::to_string(cell) + " is past the memory");
        const uint64_t v = r.bounded(words ? "word value" : "bit value", words ? 0xFFFF : kBitState | kBitDisabled);
        changes_.push_back({uint32_t(cell + (words ? img.bits.size() : 0)), uint16_t(v)});
      }
    }
    s.end = changes_.size();
    scans_.push_back(s);
    apply(i, &img);
    const size_t since = i + 1 - key_scans_.back();
    if (since >= kKeyframeScans || s.end - scans_[key_scans_.back()].begin >= kKeyframeChanges) {
      keyframes_.push_back(img);
      key_scans_.push_back(i + 1);
    }
  }
}

void Reader::apply(size_t i, Image* img) const {
  const uint32_t bits = uint32_t(img->bits.size());
  for (size_t k = scans_[i].begin; k < scans_[i].end; ++k) {
    const Change& c = changes_[k];
    if (c.cell < bits) img->bits[c.cell] = uint8_t(c.value);
    else img->words[c.cell - bits] = c.value;
  }
}

size_t Reader::scan_at(uint64_t t_us) const {
  const auto it = std::upper_bound(scans_.begin(), scans_.end(), t_us,
                                   [](uint64_t t, const Scan& s) { return t < s.t_us; });
  return it == scans_.begin() ? 0 : size_t(it - scans_.begin()) - 1;
}

size_t Reader::next_change(size_t from, int dir, const std::vector<bool>& cells) const {
  for (size_t i = from; dir > 0 ? i + 1 < scans_.size() : i > 0;) {
    i = dir > 0 ? i + 1 : i - 1;
    for (size_t k = scans_[i].begin; k < scans_[i].end; ++k)
      if (changes_[k].cell < cells.size() && cells[changes_[k].cell]) return i;
  }
  return from;
}

void Reader::each_change(size_t first, size_t last, const std::function<bool(size_t, uint32_t, uint16_t)>& f) const {
  for (size_t i = first; i <= last && i < scans_.size(); ++i)
    for (size_t k = scans_[i].begin; k < scans_[i].end; ++k)
      if (!f(i, changes_[k].cell, changes_[k].value)) return;
}

void Reader::image_after(size_t i, Image* out) const {
  const size_t applied = std::min(i + 1, scans_.size());
  const size_t k = size_t(std::upper_bound(key_scans_.begin(), key_scans_.end(), applied) - key_scans_.begin()) - 1;
  *out = keyframes_[k];
  for (size_t n = key_scans_[k]; n < applied; ++n) apply(n, out);
}

std::vector<std::string> Reader::describe_changes(size_t i) const {
  std::vector<std::string> out;
  const uint32_t bits = bit_cells();
  for (size_t k = scans_[i].begin; k < scans_[i].end; ++k) {
    const Change& c = changes_[k];
    if (c.cell < bits)
      out.push_back(bit_cell_name(c.cell) + " = " + std::to_string(c.value & kBitState) +
                    (c.value & kBitDisabled ? " (forced)" : ""));
    else
      out.push_back(word_cell_name(c.cell - bits) + " = " + std::to_string(c.value));
  }
  return out;
}

}  // namespace recording
}  // namespace plc_cell
