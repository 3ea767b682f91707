#include "plc_cell/recording/envelope.h"

#include <zlib.h>

#include "codec.h"
#include "plc_cell/recording/recording.h"

namespace plc_cell {
namespace recording {

namespace {

const char kMagic[8] = {'P', 'L', 'C', 'R', 'E', 'C', '\x1a', '\n'};

[[noreturn]] void fail(const std::string& name, size_t offset, const std::string& why) {
  throw RecordingError(name + ": offset " + std::to_string(offset) + ": " + why);
}

}  // namespace

std::string pack(const std::string& payload, uint16_t version) {
  uLongf packed_size = compressBound(payload.size());
  std::string packed(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(&packed[0]), &packed_size,
                reinterpret_cast<const Bytef*>(payload.data()), payload.size(), Z_BEST_COMPRESSION) != Z_OK)
    throw Error("recording: zlib could not compress " + std::to_string(payload.size()) + " bytes");
  packed.resize(packed_size);
  ByteWriter w;
  w.raw(kMagic, sizeof kMagic);
  w.u16(version);
  w.u64(payload.size());
  w.u32(uint32_t(crc32(0, reinterpret_cast<const Bytef*>(payload.data()), uInt(payload.size()))));
  w.u64(packed.size());
  w.bytes() += packed;
  return w.bytes();
}

std::string unpack(const std::string& file, const std::string& name, uint16_t expected) {
  if (file.compare(0, sizeof kMagic, std::string(kMagic, sizeof kMagic)) != 0)
    fail(name, 0, "not a plc_cell recording (no PLCREC magic)");
  ByteReader r(file);
  try {
    char magic[sizeof kMagic];
    r.raw(magic, sizeof magic, "magic");
    const uint16_t version = r.u16("version");
    if (version == kLineFormatVersion && expected == kFormatVersion)
      fail(name, 8, "a recording of a line of cells: open one of its cells (plc_cell monitor --recording " + name +
                        " --cell NAME)");
    if (version == kFormatVersion && expected == kLineFormatVersion)
      fail(name, 8, "a recording of one cell, not of a line");
    if (version != kFormatVersion && version != kLineFormatVersion)
      fail(name, 8, "format version " + std::to_string(version) + ", this plc_cell reads versions " +
                        std::to_string(kFormatVersion) + " and " + std::to_string(kLineFormatVersion));
    const uint64_t size = r.u64("payload size");
    if (size > kMaxPayload)
      fail(name, 10, "payload size " + std::to_string(size) + " is over the limit of " + std::to_string(kMaxPayload));
    const uint32_t crc = r.u32("checksum");
    const uint64_t packed = r.u64("packed size");
    if (packed != r.left())
      fail(name, 22, "packed size " + std::to_string(packed) + " but " + std::to_string(r.left()) +
                         " bytes follow the header (file cut short or extended)");
    // zlib's deflate packs at most about 1032:1: a larger claim is a damaged header, and
    // nothing is allocated for it.
    if (size > packed * 1032 + 64)
      fail(name, 10, "payload size " + std::to_string(size) + " cannot come from " + std::to_string(packed) +
                         " packed bytes");
    std::string payload(size, '\0');
    uLongf out_size = size;
    const int rc = uncompress(reinterpret_cast<Bytef*>(&payload[0]), &out_size,
                              reinterpret_cast<const Bytef*>(file.data() + kEnvelopeSize), packed);
    if (rc != Z_OK || out_size != size)
      fail(name, kEnvelopeSize, std::string("the packed data does not unpack to its size (zlib: ") +
                                    (rc == Z_OK ? "size differs" : zError(rc)) + ")");
    if (uint32_t(crc32(0, reinterpret_cast<const Bytef*>(payload.data()), uInt(size))) != crc)
      fail(name, 18, "checksum mismatch: the data is damaged");
    return payload;
  } catch (const FormatError& e) {
    fail(name, e.offset, e.what());
  }
}

}  // namespace recording
}  // namespace plc_cell
