#include "plc_cell/modbus/bridge.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <map>

#include <modbus/modbus.h>

#include "plc_cell/core/error.h"
#include "plc_cell/io/polled_link.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/io/transport.h"

namespace plc_cell {
namespace modbus {

using Clock = std::chrono::steady_clock;

// One line: the io layer's PolledLink over a TCP or serial Transport, with a libmodbus
// context that frames on the transport's fd (libmodbus never opens or closes it, so the
// line reconnects with the io layer's back-off, as the FATEK and TRi bridges do).
class Bridge::Line : public PolledLink {
 public:
  Line(const Device& dev, const BridgeConfig& cfg, std::function<void(const std::string&)> on_connect_error)
      : PolledLink(cfg.backoff_min_s, cfg.backoff_max_s, std::move(on_connect_error)) {
    if (!dev.tcp.empty()) {
      std::string host;
      int port;
      parse_host_port(dev.tcp, &host, &port);
      ctx_ = modbus_new_tcp(host.empty() ? "127.0.0.1" : host.c_str(), port);
      transport_ = tcp_transport(dev.tcp);
    } else {
      const SerialSettings s = parse_serial_settings(dev.rtu, "8E1");
      ctx_ = modbus_new_rtu(s.device.c_str(), s.baud, s.parity, s.data_bits, s.stop_bits);
      transport_ = serial_transport(s);
    }
    if (!ctx_) throw Error("device '" + dev.name + "': " + modbus_strerror(errno));
    link_name_ = transport_->describe();
  }
  ~Line() override {
    stop();
    modbus_free(ctx_);
  }
  using PolledLink::add_poll;
  std::vector<size_t> devices;
  size_t groups = 0;  // a line with none is not opened until a write needs it

  // f(ctx) under the link lock with the context on the open line; false when it is down.
  template <typename F>
  bool on_line(F&& f) {
    std::lock_guard<std::mutex> lk(link_mu_);
    if (!transport_->is_open()) return false;
    bind();
    f(ctx_);
    return true;
  }
  // f(ctx) under the link lock, connecting first whatever the back-off (someone waits for
  // it); throws CommError when the line cannot be opened.
  template <typename F>
  void now(F&& f) {
    transaction([&] {
      bind();
      f(ctx_);
    });
  }
  // Link lock held: the line broke, the link reconnects.
  void drop() { drop_link(); }
  int fd() const { return transport_->fd(); }

 private:
  Transport& transport() override { return *transport_; }
  void confirm() override {}  // an open line counts; the polls tell whether a device answers
  void bind() { modbus_set_socket(ctx_, transport_->fd()); }

  std::unique_ptr<Transport> transport_;
  modbus_t* ctx_ = nullptr;
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
      const size_t k = lines_.size();
      lines_.push_back(std::make_unique<Line>(dev, cfg_, [this, k](const std::string& why) { link_failed(*lines_[k], why); }));
      l = lines_.back().get();
    }
    l->devices.push_back(d);
    line_of_.push_back(l);
    l->groups += dev.groups.size();
    for (size_t g = 0; g < dev.groups.size(); ++g)
      l->add_poll(dev.groups[g].rate_hz, [this, l, d, g] { return poll_group(*l, d, g); });
  }
}

Bridge::~Bridge() { stop(); }

void Bridge::start() {
  for (auto& l : lines_)
    if (l->groups > 0) l->start();
}

void Bridge::stop() {
  for (auto& l : lines_) l->stop();
}

void Bridge::recover() {
  for (auto& l : lines_) {
    l->recover();
    std::lock_guard<std::mutex> lk(status_mu_);
    for (size_t d : l->devices) status_[d].connected = false;
  }
}

DeviceStatus Bridge::status(size_t device) const {
  std::lock_guard<std::mutex> lk(status_mu_);
  return status_.at(device);
}

// The line could not be opened (the link's thread retries after the back-off).
void Bridge::link_failed(const Line& line, const std::string& why) {
  std::lock_guard<std::mutex> lk(status_mu_);
  for (size_t d : line.devices) {
    status_[d].connected = false;
    status_[d].last_error = why;
  }
}

// Sorts a failed transaction (link lock held): an exception reply keeps the link; a
// timeout on a serial line blames only that device; anything else drops the line.
void Bridge::note_error(Line& line, size_t dev, int err) {
  const bool exception = err > MODBUS_ENOBASE && err < MODBUS_ENOBASE + 12;
  const Device& device = cfg_.devices[dev];
  // A slave that is not answering, or garbled its answer, leaves a serial line fine, but
  // its reply (or the rest of it) may still come, and would pass for the answer to the
  // next request of the same slave and size: the line is drained until quiet first.
  bool resynchronised = false;
  if (!device.rtu.empty() && (err == ETIMEDOUT || (!exception && err > MODBUS_ENOBASE))) {
    const int quiet_ms = std::max(1, int(device.timeout_s * 1000));
    resynchronised = drain_until_quiet(line.fd(), quiet_ms, 10 * quiet_ms);
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
  line.drop();
  for (size_t d : line.devices) status_[d].connected = false;
}

// The group's planned reads into r.blocks (link lock held); false at the first that fails.
bool Bridge::read_blocks(Line& line, size_t dev, GroupResult& r) {
  bool ok = false;
  line.on_line([&](modbus_t* ctx) {
    const Device& d = cfg_.devices[dev];
    modbus_set_slave(ctx, d.unit);
    const uint32_t to_us = uint32_t(d.timeout_s * 1e6);
    modbus_set_response_timeout(ctx, to_us / 1000000, to_us % 1000000);
    for (const auto& rq : r.reads) {
      std::vector<uint16_t> block(rq.count);
      int rc;
      if (rq.table == Table::Coils || rq.table == Table::DiscreteInputs) {
        std::vector<uint8_t> bits(rq.count);
        rc = rq.table == Table::Coils ? modbus_read_bits(ctx, int(rq.address), int(rq.count), bits.data())
                                      : modbus_read_input_bits(ctx, int(rq.address), int(rq.count), bits.data());
        for (uint32_t i = 0; i < rq.count; ++i) block[i] = bits[i];
      } else {
        rc = rq.table == Table::HoldingRegisters
                 ? modbus_read_registers(ctx, int(rq.address), int(rq.count), block.data())
                 : modbus_read_input_registers(ctx, int(rq.address), int(rq.count), block.data());
      }
      if (rc != int(rq.count)) {
        const int err = errno;
        r.error = std::string(table_name(rq.table)) + " " + std::to_string(rq.address) + "+" +
                  std::to_string(rq.count) + ": " + modbus_strerror(err);
        note_error(line, dev, err);
        return;
      }
      r.blocks.push_back(std::move(block));
    }
    ok = true;
  });
  if (!ok && r.error.empty()) r.error = "not connected";
  return ok;
}

void Bridge::decode_group(size_t dev, GroupResult& r) const {
  const PollGroup& g = cfg_.devices[dev].groups[r.group];
  r.values.resize(g.points.size());
  r.engineering.resize(g.points.size());
  for (size_t k = 0; k < r.reads.size(); ++k)
    for (size_t pi : r.reads[k].points) {
      const Point& p = g.points[pi];
      r.values[pi] = decode(p.enc, r.blocks[k].data() + (p.address - r.reads[k].address));
      r.engineering[pi] = r.values[pi].as_double() * p.scale + p.offset;
    }
}

// One poll of one group on the line's thread; false when the line broke.
bool Bridge::poll_group(Line& line, size_t dev, size_t group) {
  GroupResult r;
  r.device = dev;
  r.group = group;
  r.reads = plans_[dev][group];
  const auto t0 = Clock::now();
  r.ok = read_blocks(line, dev, r);
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
  if (r.ok) decode_group(dev, r);
  sink_(r);
  return line.status().connected;
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
  int rc = -1, err = 0;
  try {
    line.now([&](modbus_t* ctx) {
      modbus_set_slave(ctx, d.unit);
      const uint32_t to_us = uint32_t(d.timeout_s * 1e6);
      modbus_set_response_timeout(ctx, to_us / 1000000, to_us % 1000000);
      if (p.table == Table::Coils) {
        rc = modbus_write_bit(ctx, int(p.address), raw ? 1 : 0);
      } else {
        uint16_t regs[4];
        pack(p.enc, raw, regs);
        const int n = register_count(p.enc.type);
        rc = n == 1 ? modbus_write_register(ctx, int(p.address), regs[0])
                    : (modbus_write_registers(ctx, int(p.address), n, regs) == n ? 1 : -1);
      }
      if (rc != 1) {
        err = errno;
        note_error(line, found_dev, err);
      }
    });
  } catch (const CommError&) {
    throw Error("device '" + d.name + "' is not connected");
  }
  if (rc != 1) throw Error("write " + name + ": " + modbus_strerror(err));
  std::lock_guard<std::mutex> sl(status_mu_);
  status_[found_dev].writes++;
}

}  // namespace modbus
}  // namespace plc_cell
