#include "plc_cell/scenario/restore.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {

namespace {

std::string state_text(const Address& a, uint32_t v) {
  if (a.width == Width::Bit && is_discrete(a.area)) return v ? "ON" : "OFF";
  return std::to_string(v);
}

bool contains(const std::vector<Address>& v, const Address& a) { return std::find(v.begin(), v.end(), a) != v.end(); }

// One point put back; throws CommError (the link) or Error (the PLC refused).
std::string restore_one(LinkedPlc& plc, const FoundPoint& f) {
  const Address& a = f.point.address;
  const std::string as_found = state_text(a, f.value) + " as found";
  if (a.width == Width::Bit && is_discrete(a.area) && f.forced.value_or(false)) {
    plc.force(a, f.value != 0);
    return "forced " + as_found;
  }
  if (f.point.held) plc.unforce(a);
  plc.write(a, f.value);
  return f.point.held ? "released, " + as_found : "written back, " + as_found;
}

// The forced state of the bits put back, read again where the link tells: each one that
// differs from what was found.
std::vector<std::string> unforced_check(LinkedPlc& plc, const std::vector<const FoundPoint*>& bits) {
  std::vector<Address> addrs;
  for (const FoundPoint* f : bits) addrs.push_back(f->point.address);
  std::vector<std::string> wrong;
  if (addrs.empty()) return wrong;
  const auto now = plc.forced(addrs);
  if (!now) return wrong;
  for (size_t i = 0; i < bits.size(); ++i)
    if (bits[i]->forced && (*now)[i] != *bits[i]->forced)
      wrong.push_back(bits[i]->point.label + ": " + ((*now)[i] ? "still forced" : "not forced") + ", found " +
                      (*bits[i]->forced ? "forced" : "not forced"));
  return wrong;
}

}  // namespace

std::vector<FoundPoint> read_found(LinkedPlc& plc, const std::vector<TouchedPoint>& points) {
  std::vector<FoundPoint> out;
  std::vector<Address> addrs, bits;
  for (const auto& p : points) {
    addrs.push_back(p.address);
    if (p.address.width == Width::Bit && is_discrete(p.address.area)) bits.push_back(p.address);
  }
  const std::vector<uint32_t> values = addrs.empty() ? std::vector<uint32_t>() : plc.read(addrs);
  const auto forced = bits.empty() ? std::nullopt : plc.forced(bits);
  size_t b = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    FoundPoint f;
    f.point = points[i];
    f.value = values.at(i);
    if (points[i].address.width == Width::Bit && is_discrete(points[i].address.area)) {
      if (forced) f.forced = (*forced)[b];
      ++b;
    }
    out.push_back(f);
  }
  return out;
}

RestoreResult restore_points(LinkedPlc& plc, const std::vector<FoundPoint>& found, const std::vector<Address>& touched,
                             const RestoreOptions& opt) {
  std::vector<const FoundPoint*> todo;
  for (const auto& f : found)
    if (contains(touched, f.point.address)) todo.push_back(&f);
  RestoreResult r;
  std::vector<bool> done(todo.size(), false);
  std::vector<const FoundPoint*> bits;
  const auto deadline = std::chrono::steady_clock::now() + opt.retry_for;
  std::chrono::milliseconds backoff(100);
  bool told = false;
  for (;;) {
    try {
      for (size_t i = 0; i < todo.size(); ++i) {
        if (done[i]) continue;
        try {
          r.restored.push_back(todo[i]->point.label + ": " + restore_one(plc, *todo[i]));
          if (todo[i]->point.address.width == Width::Bit && is_discrete(todo[i]->point.address.area))
            bits.push_back(todo[i]);
        } catch (const CommError&) {
          throw;
        } catch (const Error& e) {  // the PLC refused: that point stays as it is
          r.not_restored.push_back(todo[i]->point.label + ": " + e.what());
        }
        done[i] = true;
      }
      for (const auto& w : unforced_check(plc, bits)) r.not_restored.push_back(w);
      return r;
    } catch (const CommError& e) {
      const bool out_of_time = std::chrono::steady_clock::now() >= deadline;
      if (!out_of_time && !told && opt.waiting) opt.waiting(e.what());
      told = true;
      if (out_of_time || (opt.wait && opt.wait(backoff))) {
        for (size_t i = 0; i < todo.size(); ++i)
          if (!done[i]) r.not_restored.push_back(todo[i]->point.label + ": not put back (" + e.what() + ")");
        return r;
      }
      backoff = std::min(backoff * 2, std::chrono::milliseconds(2000));
    }
  }
}

// ---- the journal ----

RestoreJournal::~RestoreJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void RestoreJournal::append(const std::string& line) {
  const std::string l = line + "\n";
  if (fd_ < 0 || ::write(fd_, l.data(), l.size()) != ssize_t(l.size()) || ::fdatasync(fd_) != 0)
    throw Error("cannot write the restore journal " + path_ + ": " + std::strerror(errno));
}

void RestoreJournal::begin(const std::string& target, const std::string& case_name,
                           const std::vector<FoundPoint>& found) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error("cannot write the restore journal " + path_ + ": " + std::strerror(errno));
  append("plc_cell restore journal 1");
  append("target " + target);
  append("case " + case_name);
  for (const auto& f : found)
    append("found " + format_address(f.point.address) + " " + std::to_string(f.value) + " " +
           (f.forced ? (*f.forced ? "1" : "0") : "-") + " " + (f.point.held ? "1" : "0") + " " + f.point.label);
}

void RestoreJournal::touched(const Address& a) { append("touched " + format_address(a)); }

void RestoreJournal::remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(path_.c_str());
}

std::optional<RestoreJournal::Left> RestoreJournal::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  Left left;
  std::string line;
  int n = 0;
  auto bad = [&](const std::string& why) { return Error(path + ":" + std::to_string(n) + ": " + why); };
  while (std::getline(in, line)) {
    ++n;
    std::istringstream s(line);
    std::string kind;
    s >> kind;
    std::string rest;
    std::getline(s >> std::ws, rest);
    if (n == 1) {
      if (line != "plc_cell restore journal 1") throw bad("not a plc_cell restore journal");
    } else if (kind == "target") {
      left.target = rest;
    } else if (kind == "case") {
      left.case_name = rest;
    } else if (kind == "found" || kind == "touched") {
      std::istringstream f(rest);
      std::string addr, forced, held;
      FoundPoint p;
      f >> addr;
      try {
        p.point.address = parse_address(addr);
      } catch (const Error& e) {
        throw bad(e.what());
      }
      if (kind == "touched") {
        left.touched.push_back(p.point.address);
        continue;
      }
      if (!(f >> p.value >> forced >> held) || (forced != "0" && forced != "1" && forced != "-"))
        throw bad("a found point is ADDRESS VALUE FORCED HELD LABEL");
      if (forced != "-") p.forced = forced == "1";
      p.point.held = held == "1";
      std::getline(f >> std::ws, p.point.label);
      left.found.push_back(p);
    } else if (!line.empty()) {
      throw bad("unknown line '" + line + "'");
    }
  }
  return left;
}

}  // namespace scenario
}  // namespace plc_cell
