#include "plc_cell/fatek/clink.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <condition_variable>
#include <map>
#include <mutex>
#include <cerrno>
#include <cstring>

#include <unistd.h>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/fatek/serial_port.h"
#include "clink_port.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace fatek {

namespace {

// FATEK frames over the COM port's own line (the port opens, reopens and closes it).
class ComPortTransport : public Transport {
 public:
  explicit ComPortTransport(std::shared_ptr<ComPort> port) : port_(std::move(port)) {}
  void open() override {
    if (port_->fd() < 0) throw CommError(describe() + ": " + port_->last_error());
  }
  void close() override { port_->lost("closed"); }
  bool is_open() const override { return port_->is_open(); }
  void send(const std::string& b, int timeout_ms) override {
    open();
    if (!write_all(port_->fd(), b.data(), b.size(), timeout_ms)) {
      port_->lost("write failed");
      throw ConnectionClosed(describe() + ": write failed");
    }
  }
  size_t recv(char* buf, size_t n, int timeout_ms) override {
    open();
    const int fd = port_->fd();
    // The fd is non-blocking: try first, wait only when nothing is there yet.
    for (int pass = 0; pass < 2; ++pass) {
      const ssize_t r = ::read(fd, buf, n);
      if (r > 0) return size_t(r);
      // A socket reads 0 at EOF; a tty with VMIN=0 reads 0 when it has nothing yet, but
      // not once poll() said it was readable: that is a hang-up (device gone).
      const bool nothing =
          r == 0 ? !port_->line().is_tcp() && pass == 0 : (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR);
      if (!nothing) {
        port_->lost(r < 0 ? std::strerror(errno) : port_->line().is_tcp() ? "connection closed" : "hang-up");
        throw ConnectionClosed(describe() + ": connection closed");
      }
      if (pass == 0 && !wait_readable(fd, timeout_ms)) return 0;
    }
    return 0;
  }
  std::string describe() const override { return port_->line().to_string(); }
  void resynchronise(int quiet_ms) override { port_->resynchronise(quiet_ms); }

 private:
  std::shared_ptr<ComPort> port_;
};

}  // namespace

ClinkPorts::ClinkPorts() = default;

// The ports may be shared with FUN150 and outlive this: wait for our own transaction
// (cancelled where it can be) so the port's thread never runs it on a Port that is gone.
ClinkPorts::~ClinkPorts() {
  for (auto& p : ports_) {
    if (!p) continue;
    std::unique_lock<std::mutex> lk(p->mu);
    p->stop = true;
    p->cancel = true;
    p->cv.wait(lk, [&] { return !p->has_job; });
  }
}

void ClinkPorts::set_port(int n, std::unique_ptr<Transport> t, int timeout_ms) {
  if (n < 1 || n > 4) throw Error("FUN151 port " + std::to_string(n) + " outside 1..4");
  try {
    t->open();  // now, so nothing that arrives before the first transaction is flushed away
  } catch (const std::exception&) {
    // not there yet: the first transaction opens it (and reports the failure)
  }
  add(std::make_shared<ComPort>(n), std::move(t), timeout_ms);
}

void ClinkPorts::set_port(std::shared_ptr<ComPort> port, int timeout_ms) {
  const int n = port->number();
  if (n < 1 || n > 4) throw Error("FUN151 port " + std::to_string(n) + " outside 1..4");
  auto t = std::make_unique<ComPortTransport>(port);
  add(std::move(port), std::move(t), timeout_ms);
}

void ClinkPorts::add(std::shared_ptr<ComPort> port, std::unique_ptr<Transport> t, int timeout_ms) {
  auto p = std::make_unique<Port>();
  ClientOptions o;
  o.timeout_ms = timeout_ms;
  o.retries = 0;  // the ladder program decides about repeating
  p->client = std::make_unique<Client>(std::move(t), o);
  p->timeout_ms = timeout_ms;
  const int n = port->number();
  p->com = std::move(port);
  ports_[size_t(n)] = std::move(p);
}

bool ClinkPorts::has(int n) const { return n >= 1 && n <= 4 && ports_[size_t(n)]; }
ClinkPorts::Port* ClinkPorts::port(int n) { return has(n) ? ports_[size_t(n)].get() : nullptr; }

ComLine clink_line(const std::string& where) {
  ComLine l;
  if (where.rfind("tcp:", 0) == 0) {
    std::string host;
    int port = 0;
    parse_host_port(where.substr(4), &host, &port);
    l.tcp = (host.empty() ? "127.0.0.1" : host) + ":" + std::to_string(port);
  } else {
    l.serial = parse_serial_settings(where, "7E1");
  }
  return l;
}

ClinkSettings read_clink_settings(const YAML::Node& f, const std::string& file) {
  ClinkSettings s;
  if (!f) return s;
  const YamlReader r(file);
  r.only(f, "fatek", {"ports", "timeout_ms"});
  if (f["timeout_ms"]) s.timeout_ms = r.integer(f["timeout_ms"], "fatek.timeout_ms", 1, 60000);
  const YAML::Node ports = f["ports"];
  if (!ports) return s;
  if (!ports.IsMap()) r.fail(ports, "fatek.ports", "expected a mapping of ports 1..4 to lines (1: /dev/ttyS1:9600:7E1)");
  for (const auto& kv : ports) {
    const std::string k = "fatek.ports." + r.str(kv.first, "fatek.ports");
    const int n = r.integer(kv.first, k, INT_MIN, INT_MAX);
    if (n < 1 || n > 4) r.fail(kv.first, k, "FUN151 port " + std::to_string(n) + " outside 1..4");
    const std::string where = r.str(kv.second, k);
    if (where.rfind("tcp:", 0) == 0) {
      r.checked(kv.second, k, [&] {
        std::string host;
        int port = 0;
        parse_host_port(where.substr(4), &host, &port);
      });
    } else {
      r.serial_line(kv.second, k, "7E1");
    }
    s.ports[n] = where;
  }
  return s;
}

std::shared_ptr<ClinkPorts> ClinkPorts::from_settings(const ClinkSettings& s) {
  auto ports = std::make_shared<ClinkPorts>();
  for (const auto& p : s.ports) ports->set_port(std::make_shared<ComPort>(p.first, clink_line(p.second)), s.timeout_ms);
  return ports;
}

std::shared_ptr<ClinkPorts> ClinkPorts::on(const ComPorts& com, int timeout_ms) {
  auto ports = std::make_shared<ClinkPorts>();
  for (const int n : com.numbers())
    if (n >= 1 && n <= 4) ports->set_port(com.get(n), timeout_ms);
  return ports;
}

std::shared_ptr<ClinkPorts> ClinkPorts::from_yaml(const YAML::Node& f, const std::string& file) {
  return from_settings(read_clink_settings(f, file));
}

}  // namespace fatek
}  // namespace plc_cell
