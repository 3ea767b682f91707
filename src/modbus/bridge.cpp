#include "plc_cell/modbus/bridge.h"

#include <algorithm>
#include <cerrno>
#include <cmath>

#include <modbus/modbus.h>

#include "plc_cell/core/error.h"
#include "plc_cell/io/backoff.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/io/transport.h"

namespace plc_cell {
namespace modbus {

using Clock = std::chrono::steady_clock;

struct Bridge::Line {
  std::string name;
  std::vector<size_t> devices;
  modbus_t* ctx = nullptr;
  bool connected = false;
  Backoff backoff{0, 0};
  Clock::time_point next_attempt{};
  std::mutex mu;  // the line: one transaction at a time (polls and writes)
  std::condition_variable cv;
  bool stop = false, recover = false;
  std::thread thread;
};

Bridge::Bridge(BridgeConfig cfg, Sink sink) : cfg_(std::move(cfg)), sink_(std::move(sink)) {
  std::map<std::string, Line*> by_name;
  status_.resize(cfg_.devices.size());
  for (size_t d = 0; d < cfg_.devices.size(); ++d) {
    const Device& dev = cfg_.devices[d];
    plans_.emplace_back();
    for (const auto& g : dev.groups) plans_.back().push_back(plan_reads(g.points, dev.max_gap));
    Line*& l = by_name[dev.line()];
    if (!l) {
      lines_.push_back(std::make_unique<Line>());
      l = lines_.back().get();
      l->name = dev.line();
      l->backoff = Backoff(cfg_.backoff_min_s, cfg_.backoff_max_s);
      if (!dev.tcp.empty()) {
        std::string host;
        int port;
        parse_host_port(dev.tcp, &host, &port);
        l->ctx = modbus_new_tcp(host.c_str(), port);
      } else {
        const SerialSettings s = parse_serial_settings(dev.rtu, "8E1");
        l->ctx = modbus_new_rtu(s.device.c_str(), s.baud, s.parity, s.data_bits, s.stop_bits);
      }
      if (!l->ctx) throw Error("device '" + dev.name + "': " + modbus_strerror(errno));
    }
    l->devices.push_back(d);
    line_of_.push_back(l);
  }
}

Bridge::~Bridge() {
  stop();
  for (auto& l : lines_) {
    if (l->connected) modbus_close(l->ctx);
    modbus_free(l->ctx);
  }
}

void Bridge::start() {
  for (auto& l : lines_) {
    if (l->thread.joinable()) continue;
    l->stop = false;
    Line* p = l.get();
    l->thread = std::thread([this, p] { run(*p); });
  }
}

void Bridge::stop() {
  for (auto& l : lines_) {
    {
      std::lock_guard<std::mutex> lk(l->mu);
      l->stop = true;
    }
    l->cv.notify_all();
    if (l->thread.joinable()) l->thread.join();
  }
}

void Bridge::recover() {
  for (auto& l : lines_) {
    {
      std::lock_guard<std::mutex> lk(l->mu);
      if (l->connected) modbus_close(l->ctx);
      l->connected = false;
      l->backoff.reset();
      l->next_attempt = Clock::now();
      l->recover = true;
    }
    l->cv.notify_all();
  }
}

DeviceStatus Bridge::status(size_t device) const {
  std::lock_guard<std::mutex> lk(status_mu_);
  return status_.at(device);
}

// Called with line.mu held.
bool Bridge::ensure_connected(Line& line) {
  if (line.connected) return true;
  if (Clock::now() < line.next_attempt) return false;
  if (modbus_connect(line.ctx) == 0) {
    line.connected = true;
    line.backoff.reset();
  } else {
    line.next_attempt = Clock::now() + std::chrono::microseconds(int64_t(line.backoff.failed() * 1e6));
    const std::string why = std::string("connect: ") + modbus_strerror(errno);
    std::lock_guard<std::mutex> lk(status_mu_);
    for (size_t d : line.devices) {
      status_[d].connected = false;
      status_[d].last_error = why;
    }
  }
  return line.connected;
}

// Sorts a failed transaction: an exception reply keeps the link; a timeout on a
// serial line blames only that device; anything else drops the connection.
void Bridge::note_error(Line& line, size_t dev, int err) {
  const bool exception = err > MODBUS_ENOBASE && err < MODBUS_ENOBASE + 12;
  const Device& device = cfg_.devices[dev];
  // A slave that is not answering, or garbled its answer, leaves a serial line fine, but
  // its reply (or the rest of it) may still come, and would pass for the answer to the
  // next request of the same slave and size: the line is drained until quiet first.
  bool resynchronised = false;
  if (!device.rtu.empty() && (err == ETIMEDOUT || (!exception && err > MODBUS_ENOBASE))) {
    const int quiet_ms = std::max(1, int(device.timeout_s * 1000));
    resynchronised = drain_until_quiet(modbus_get_socket(line.ctx), quiet_ms, 10 * quiet_ms);
    if (resynchronised) modbus_flush(line.ctx);
  }
  std::lock_guard<std::mutex> lk(status_mu_);
  DeviceStatus& s = status_[dev];
  s.last_error = modbus_strerror(err);
  if (exception) {
    s.exceptions++;
    char code[8];
    snprintf(code, sizeof code, "%02X ", err - MODBUS_ENOBASE);
    s.last_exception = code + s.last_error;
    return;
  }
  if (err == ETIMEDOUT) s.timeouts++;
  else s.io_errors++;
  if (resynchronised && err == ETIMEDOUT) return;  // the line itself is fine
  modbus_close(line.ctx);
  line.connected = false;
  // A link that worked is retried after the shortest delay; failing again, longer ones.
  line.backoff.reset();
  line.next_attempt = Clock::now() + std::chrono::microseconds(int64_t(line.backoff.failed() * 1e6));
  for (size_t d : line.devices) status_[d].connected = false;
}

void Bridge::poll_group(Line& line, size_t dev, size_t group) {
  const Device& d = cfg_.devices[dev];
  const PollGroup& g = d.groups[group];
  GroupResult r;
  r.device = dev;
  r.group = group;
  r.reads = plans_[dev][group];
  {
    std::unique_lock<std::mutex> lk(line.mu);
    if (!ensure_connected(line)) {
      r.error = "not connected";
    } else {
      modbus_set_slave(line.ctx, d.unit);
      const uint32_t to_us = uint32_t(d.timeout_s * 1e6);
      modbus_set_response_timeout(line.ctx, to_us / 1000000, to_us % 1000000);
      const auto t0 = Clock::now();
      r.ok = true;
      for (const auto& rq : r.reads) {
        std::vector<uint16_t> block(rq.count);
        int rc;
        if (rq.table == Table::Coils || rq.table == Table::DiscreteInputs) {
          std::vector<uint8_t> bits(rq.count);
          rc = rq.table == Table::Coils ? modbus_read_bits(line.ctx, int(rq.address), int(rq.count), bits.data())
                                        : modbus_read_input_bits(line.ctx, int(rq.address), int(rq.count), bits.data());
          for (uint32_t i = 0; i < rq.count; ++i) block[i] = bits[i];
        } else {
          rc = rq.table == Table::HoldingRegisters
                   ? modbus_read_registers(line.ctx, int(rq.address), int(rq.count), block.data())
                   : modbus_read_input_registers(line.ctx, int(rq.address), int(rq.count), block.data());
        }
        if (rc != int(rq.count)) {
          const int err = errno;
          r.ok = false;
          r.error = std::string(table_name(rq.table)) + " " + std::to_string(rq.address) + "+" +
                    std::to_string(rq.count) + ": " + modbus_strerror(err);
          note_error(line, dev, err);
          break;
        }
        r.blocks.push_back(std::move(block));
      }
      if (r.ok) {
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        std::lock_guard<std::mutex> sl(status_mu_);
        DeviceStatus& s = status_[dev];
        s.connected = true;
        s.polls++;
        s.latency_last_ms = ms;
        s.latency_max_ms = std::max(s.latency_max_ms, ms);
        s.latency_sum_ms += ms;
        s.latency_n++;
      }
    }
  }
  if (r.ok) {
    r.values.resize(g.points.size());
    r.engineering.resize(g.points.size());
    for (size_t k = 0; k < r.reads.size(); ++k)
      for (size_t pi : r.reads[k].points) {
        const Point& p = g.points[pi];
        r.values[pi] = decode(p.enc, r.blocks[k].data() + (p.address - r.reads[k].address));
        r.engineering[pi] = r.values[pi].as_double() * p.scale + p.offset;
      }
  }
  sink_(r);
}

void Bridge::run(Line& line) {
  struct Due {
    size_t dev, group;
    Clock::time_point at;
    Clock::duration period;
  };
  std::vector<Due> due;
  const auto now = Clock::now();
  for (size_t d : line.devices)
    for (size_t g = 0; g < cfg_.devices[d].groups.size(); ++g)
      due.push_back({d, g, now,
                     std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / cfg_.devices[d].groups[g].rate_hz))});
  if (due.empty()) return;
  for (;;) {
    size_t next = 0;
    for (size_t i = 1; i < due.size(); ++i)
      if (due[i].at < due[next].at) next = i;
    {
      std::unique_lock<std::mutex> lk(line.mu);
      line.cv.wait_until(lk, due[next].at, [&] { return line.stop || line.recover; });
      if (line.stop) return;
      if (line.recover) {
        line.recover = false;
        for (auto& x : due) x.at = Clock::now();
        continue;
      }
    }
    Due& dn = due[next];
    poll_group(line, dn.dev, dn.group);
    dn.at += dn.period;
    if (dn.at < Clock::now()) dn.at = Clock::now();  // overrun: do not queue a burst
  }
}

void Bridge::write(const std::string& name, double value) {
  const std::string dev_name = name.find('/') == std::string::npos ? "" : name.substr(0, name.find('/'));
  const std::string pt_name = name.substr(name.find('/') == std::string::npos ? 0 : name.find('/') + 1);
  const Point* found = nullptr;
  size_t found_dev = 0;
  for (size_t d = 0; d < cfg_.devices.size(); ++d) {
    if (!dev_name.empty() && cfg_.devices[d].name != dev_name) continue;
    for (const auto& g : cfg_.devices[d].groups)
      for (const auto& p : g.points)
        if (p.name == pt_name) {
          if (found) throw Error("point '" + name + "' is ambiguous: write it as device/point");
          found = &p;
          found_dev = d;
        }
  }
  if (!found) throw Error("no point '" + name + "'");
  const Point& p = *found;
  if (!p.writable()) throw Error("point '" + name + "' is a " + table_name(p.table) + ": read-only");
  uint64_t raw;
  try {
    raw = to_raw(p.enc.type, value, p.scale, p.offset);
  } catch (const Error& e) {
    throw Error("point '" + name + "' (" + point_type_name(p.enc.type) + "): " + e.what());
  }
  const Device& d = cfg_.devices[found_dev];
  Line& line = *line_of_[found_dev];
  std::lock_guard<std::mutex> lk(line.mu);
  line.next_attempt = std::min(line.next_attempt, Clock::now());  // a write is worth a connection attempt now
  if (!ensure_connected(line)) throw Error("device '" + d.name + "' is not connected");
  modbus_set_slave(line.ctx, d.unit);
  const uint32_t to_us = uint32_t(d.timeout_s * 1e6);
  modbus_set_response_timeout(line.ctx, to_us / 1000000, to_us % 1000000);
  int rc;
  if (p.table == Table::Coils) {
    rc = modbus_write_bit(line.ctx, int(p.address), raw ? 1 : 0);
  } else {
    uint16_t regs[4];
    pack(p.enc, raw, regs);
    const int n = register_count(p.enc.type);
    rc = n == 1 ? modbus_write_register(line.ctx, int(p.address), regs[0])
                : (modbus_write_registers(line.ctx, int(p.address), n, regs) == n ? 1 : -1);
  }
  if (rc != 1) {
    const int err = errno;
    note_error(line, found_dev, err);
    throw Error("write " + name + ": " + modbus_strerror(err));
  }
  std::lock_guard<std::mutex> sl(status_mu_);
  status_[found_dev].writes++;
}

}  // namespace modbus
}  // namespace plc_cell
