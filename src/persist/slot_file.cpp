#include "plc_cell/persist/slot_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "plc_cell/core/error.h"
#include "plc_cell/persist/crc32.h"

namespace plc_cell {
namespace persist {
namespace {

constexpr uint32_t kMagic = 0x31525350;  // "PSR1" little-endian
constexpr size_t kHeader = 20;           // magic 4, seq 8, length 4, crc 4

void put(uint8_t* p, uint64_t v, int n) {
  for (int k = 0; k < n; ++k) p[k] = uint8_t(v >> (8 * k));
}
uint64_t get(const uint8_t* p, int n) {
  uint64_t v = 0;
  for (int k = 0; k < n; ++k) v |= uint64_t(p[k]) << (8 * k);
  return v;
}

// CRC over the header's first 16 bytes and the payload.
uint32_t slot_crc(const uint8_t* header, const uint8_t* payload, size_t n) {
  return crc32(payload, n, crc32(header, 16));
}

void encode_slot(uint8_t* dst, uint64_t seq, const std::vector<uint8_t>& payload) {
  put(dst, kMagic, 4);
  put(dst + 4, seq, 8);
  put(dst + 12, payload.size(), 4);
  std::memcpy(dst + kHeader, payload.data(), payload.size());
  put(dst + 16, slot_crc(dst, dst + kHeader, payload.size()), 4);
}

std::string sys_error(const std::string& what, const std::string& path) {
  return what + " " + path + ": " + std::strerror(errno);
}

void write_all(int fd, const uint8_t* p, size_t n, off_t off, const std::string& path) {
  while (n) {
    const ssize_t w = ::pwrite(fd, p, n, off);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw Error(sys_error("cannot write", path));
    p += w;
    n -= size_t(w);
    off += w;
  }
}

std::string folder_of(const std::string& path) {
  const auto k = path.rfind('/');
  return k == std::string::npos ? "." : k == 0 ? "/" : path.substr(0, k);
}

}  // namespace

std::vector<Slot> read_slots(const std::string& path, std::vector<std::string>* problems) {
  std::vector<Slot> out;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (errno != ENOENT) problems->push_back(sys_error("cannot open", path));
    return out;
  }
  std::vector<uint8_t> data;
  uint8_t chunk[65536];
  for (;;) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    data.insert(data.end(), chunk, chunk + n);
  }
  ::close(fd);
  // The file is always written whole: two equal slots. Slot 0's length says where slot 1
  // starts, so a truncated or extended file is named as such even when slot 0 is intact.
  size_t half = data.size() / 2;
  bool sized = false;
  if (data.size() >= kHeader && get(data.data(), 4) == kMagic) {
    const size_t slot = kHeader + size_t(get(data.data() + 12, 4));
    if (data.size() != 2 * slot)
      problems->push_back(path + ": file size " + std::to_string(data.size()) + ", two slots of " + std::to_string(slot) +
                          " bytes expected (truncated?)");
    half = slot;
    sized = true;
  }
  const size_t offsets[2] = {0, half};
  for (int s = 0; s < 2; ++s) {
    const std::string where = path + " slot " + std::to_string(s);
    const size_t off = offsets[s];
    if (s == 1 && !sized && (data.size() % 2 || off < kHeader)) {
      problems->push_back(where + ": file size " + std::to_string(data.size()) + " is not two whole slots (truncated?)");
      continue;
    }
    if (data.size() < off + kHeader) {
      problems->push_back(where + ": truncated");
      continue;
    }
    const uint8_t* h = data.data() + off;
    const uint64_t seq = get(h + 4, 8);
    const size_t len = size_t(get(h + 12, 4));
    if (get(h, 4) != kMagic) {
      if (seq != 0 || get(h, 4) != 0) problems->push_back(where + ": bad magic");  // all zero = never written
      continue;
    }
    if (data.size() - off - kHeader < len) {
      problems->push_back(where + ": truncated payload");
      continue;
    }
    if (slot_crc(h, h + kHeader, len) != uint32_t(get(h + 16, 4))) {
      problems->push_back(where + ": CRC mismatch (torn or corrupt)");
      continue;
    }
    out.push_back({seq, std::vector<uint8_t>(h + kHeader, h + kHeader + len), where});
  }
  return out;
}

SlotFile::SlotFile(const std::string& path, uint64_t seq, const std::vector<uint8_t>& payload)
    : path_(path), slot_size_(kHeader + payload.size()), buf_(slot_size_) {
  std::vector<uint8_t> whole(2 * slot_size_, 0);
  encode_slot(whole.data(), seq, payload);
  const std::string tmp = path + ".tmp";
  const int t = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (t < 0) throw Error(sys_error("cannot create", tmp));
  try {
    write_all(t, whole.data(), whole.size(), 0, tmp);
    if (::fsync(t) != 0) throw Error(sys_error("cannot fsync", tmp));
  } catch (...) {
    ::close(t);
    throw;
  }
  ::close(t);
  if (::rename(tmp.c_str(), path.c_str()) != 0) throw Error(sys_error("cannot rename to", path));
  const int dir = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);  // the rename itself is durable
    ::close(dir);
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error(sys_error("cannot open", path));
}

SlotFile::~SlotFile() {
  if (fd_ >= 0) ::close(fd_);
}

void SlotFile::write(uint64_t seq, const std::vector<uint8_t>& payload, bool sync) {
  if (kHeader + payload.size() != slot_size_) throw Error("store " + path_ + ": payload size changed");
  encode_slot(buf_.data(), seq, payload);
  write_all(fd_, buf_.data(), buf_.size(), off_t(next_) * off_t(slot_size_), path_);
  if (sync && ::fdatasync(fd_) != 0) throw Error(sys_error("cannot fdatasync", path_));
  next_ ^= 1;
}

}  // namespace persist
}  // namespace plc_cell
