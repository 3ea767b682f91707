#include "plc_cell/recording/line_recording.h"

#include "codec.h"
#include "plc_cell/recording/envelope.h"

namespace plc_cell {
namespace recording {

namespace {

constexpr size_t kMaxLineText = size_t(64) << 20;
constexpr uint64_t kMaxLineCells = 100000;

}  // namespace

LineRecorder::LineRecorder(LineRecordingInfo info, std::vector<std::pair<std::string, RecordingInfo>> cells)
    : info_(std::move(info)) {
  for (auto& c : cells) {
    names_.push_back(c.first);
    recorders_.push_back(std::make_unique<Recorder>(std::move(c.second)));
  }
}

void LineRecorder::set_failure(uint64_t t_us, const std::string& text) {
  info_.failure_us = t_us;
  info_.failure = text;
  for (auto& r : recorders_) r->set_failure(t_us, text);
}

std::string LineRecorder::bytes() const {
  ByteWriter w;
  w.string(info_.source);
  w.string(info_.line);
  w.u8(info_.failure_us ? 1 : 0);
  if (info_.failure_us) {
    w.varint(*info_.failure_us);
    w.string(info_.failure);
  }
  w.varint(info_.wires.size());
  for (const auto& s : info_.wires) w.string(s);
  w.varint(recorders_.size());
  for (size_t i = 0; i < recorders_.size(); ++i) {
    w.string(names_[i]);
    w.string(recorders_[i]->payload());
  }
  return pack(w.bytes(), kLineFormatVersion);
}

void LineRecorder::save(const std::string& path) const { write_recording_file(path, bytes()); }

LineReader LineReader::load(const std::string& path) { return parse(read_recording_file(path), path); }

LineReader LineReader::parse(const std::string& bytes, const std::string& name) {
  const std::string payload = unpack(bytes, name, kLineFormatVersion);
  LineReader out;
  ByteReader r(payload);
  std::vector<std::pair<std::string, std::string>> parts;
  try {
    out.info_.source = r.string("source", kMaxLineText);
    out.info_.line = r.string("line name", 4096);
    const uint8_t failed = r.u8("failure flag");
    if (failed > 1) r.fail("failure flag " + std::to_string(failed) + " is not 0 or 1");
    if (failed) {
      out.info_.failure_us = r.varint("failure instant");
      out.info_.failure = r.string("failure text", kMaxLineText);
    }
    const uint64_t wires = r.bounded("wire count", r.left());
    for (uint64_t i = 0; i < wires; ++i) out.info_.wires.push_back(r.string("wire", 4096));
    const uint64_t cells = r.bounded("cell count", std::min<uint64_t>(kMaxLineCells, r.left()));
    for (uint64_t i = 0; i < cells; ++i) {
      std::string cell = r.string("cell name", 4096);
      parts.emplace_back(std::move(cell), r.string("cell recording", r.left()));
    }
    if (r.left()) r.fail(std::to_string(r.left()) + " bytes after the last cell");
  } catch (const FormatError& e) {
    throw RecordingError(name + ": offset " + std::to_string(e.offset) + " of the unpacked data: " + e.what());
  }
  for (auto& p : parts) out.cells_.emplace_back(p.first, Reader::parse_payload(p.second, name + " (cell " + p.first + ")"));
  return out;
}

const Reader* LineReader::find(const std::string& name) const {
  for (const auto& c : cells_)
    if (c.first == name) return &c.second;
  return nullptr;
}

uint16_t format_version(const std::string& bytes) {
  if (bytes.size() < 10) return 0;
  return uint16_t(uint8_t(bytes[8]) | uint16_t(uint8_t(bytes[9])) << 8);
}

}  // namespace recording
}  // namespace plc_cell
