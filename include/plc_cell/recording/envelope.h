#pragma once
// The file around a recording's payload: an 8-byte magic, the format version, the
// payload's size and CRC-32, and the payload compressed with zlib (docs/recordings.md,
// "File format").
#include <cstdint>
#include <string>

namespace plc_cell {
namespace recording {

constexpr size_t kEnvelopeSize = 30;
// A payload larger than this is refused before anything is allocated for it.
constexpr uint64_t kMaxPayload = uint64_t(1) << 31;

// A payload in its envelope: the file's bytes.
std::string pack(const std::string& payload);
// The payload of a file's bytes; throws RecordingError "name: offset N: why".
std::string unpack(const std::string& file, const std::string& name);

}  // namespace recording
}  // namespace plc_cell
