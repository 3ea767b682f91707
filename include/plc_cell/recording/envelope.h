#pragma once
// The file around a recording's payload: an 8-byte magic, the format version, the
// payload's size and CRC-32, and the payload compressed with zlib (docs/recordings.md,
// "File format").
#include <cstdint>
#include <string>

#include "plc_cell/recording/recording.h"

namespace plc_cell {
namespace recording {

constexpr size_t kEnvelopeSize = 30;
// A payload larger than this is refused before anything is allocated for it.
constexpr uint64_t kMaxPayload = uint64_t(1) << 31;

// A payload in its envelope: the file's bytes. version: kFormatVersion for a cell's
// recording, kLineFormatVersion for a line's (line_recording.h).
std::string pack(const std::string& payload, uint16_t version = kFormatVersion);
// The payload of a file's bytes, which must be of the format version given; throws
// RecordingError "name: offset N: why" (a line's recording where a cell's is expected is
// said so).
std::string unpack(const std::string& file, const std::string& name, uint16_t version = kFormatVersion);

}  // namespace recording
}  // namespace plc_cell
