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

// FUN151's use of one COM port: one transaction at a time, run on the port's thread
// (shared with FUN150 on the same port). A job is a FATEK request (MD0) or raw bytes out
// and/or a raw message in (MD1/MD2).
struct ClinkPorts::Port {
  struct Raw {
    std::string tx;
    bool rx = false;
    uint8_t start = 0, end = 0;  // 0 = none (a quiet gap ends the message)
    int gap_ms = 12;
    int timeout_ms = 500;        // <= 0: wait until a message arrives or the job is cancelled
  };
  std::shared_ptr<ComPort> com;
  std::unique_ptr<Client> client;
  int timeout_ms = 500;
  std::mutex mu;
  std::condition_variable cv;
  bool has_job = false, done = false, stop = false;
  std::atomic<bool> cancel{false};
  bool raw_job = false;
  Request job;
  Raw raw;
  Response rsp;
  std::string received;
  ClinkResult result = ClinkResult::Ok;

  ClinkResult run_raw(const Raw& r, std::string* in) {
    Transport& t = client->transport();
    if (!r.tx.empty()) t.send(r.tx, timeout_ms);
    if (!r.rx) return ClinkResult::Ok;
    const auto t0 = std::chrono::steady_clock::now();
    auto last = t0;
    bool started = r.start == 0;
    char buf[256];
    for (;;) {
      if (cancel) return ClinkResult::Timeout;
      const auto now = std::chrono::steady_clock::now();
      const auto ms = [](auto d) { return std::chrono::duration_cast<std::chrono::milliseconds>(d).count(); };
      if (!in->empty() && r.end == 0 && ms(now - last) >= r.gap_ms) return ClinkResult::Ok;
      if (in->empty() && r.timeout_ms > 0 && ms(now - t0) >= r.timeout_ms) return ClinkResult::Timeout;
      const int wait = in->empty() || r.end != 0 ? 20 : std::max(1, r.gap_ms - int(ms(now - last)));
      const size_t n = t.recv(buf, sizeof buf, wait);
      if (n) last = std::chrono::steady_clock::now();
      for (size_t i = 0; i < n; ++i) {
        const uint8_t b = uint8_t(buf[i]);
        if (!started) {
          if (b != r.start) continue;  // bytes before the start code are dropped
          started = true;
        }
        in->push_back(char(b));
        if (in->size() > 511) return ClinkResult::BadData;
        if (r.end != 0 && b == r.end) return ClinkResult::Ok;
      }
    }
  }

  // The instruction set has_job under mu: hand the transaction to the port's thread.
  void post() {
    com->submit([this] { run_one(); });
  }

  void run_one() {
    std::unique_lock<std::mutex> lk(mu);
    if (stop) {
      has_job = false;
      cv.notify_all();
      return;
    }
    const bool is_raw = raw_job;
    Request req = job;
    Raw r = raw;
    lk.unlock();
    Response out;
    std::string in;
    ClinkResult res = ClinkResult::Ok;
    try {
      if (is_raw) res = run_raw(r, &in);
      else out = client->transact(req);
    } catch (const PlcError&) {
      res = ClinkResult::BadData;  // the slave answered with an error code
    } catch (const CommError& e) {
      res = std::string(e.what()).find("no answer") != std::string::npos ? ClinkResult::Timeout : ClinkResult::BadData;
    } catch (const std::exception&) {
      res = ClinkResult::BadData;
    }
    lk.lock();
    rsp = std::move(out);
    received = std::move(in);
    result = res;
    has_job = false;
    done = true;
    cv.notify_all();
  }
};

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

namespace {

// Data codes 0..13 of the CLINK table.
bool data_address(uint32_t code, uint32_t ref, Address* out) {
  static const struct {
    Area area;
    Width width;
    uint32_t max;
  } kTypes[] = {{Area::X, Width::Bit, 255},  {Area::Y, Width::Bit, 255},   {Area::M, Width::Bit, 1911},
                {Area::S, Width::Bit, 999},  {Area::T, Width::Bit, 255},   {Area::C, Width::Bit, 255},
                {Area::X, Width::Word, 240}, {Area::Y, Width::Word, 240},  {Area::M, Width::Word, 1896},
                {Area::S, Width::Word, 984}, {Area::RT, Width::Word, 255}, {Area::RC, Width::Word, 199},
                {Area::R, Width::Word, 3839}, {Area::D, Width::Word, 4095}};
  const auto& t = kTypes[code];
  if (ref > t.max || (code >= 6 && code <= 9 && ref % 8 != 0)) return false;
  *out = Address{t.area, t.width, ref};
  return true;
}

struct Instance {
  bool prev_en = false;
  bool active = false;   // started by an EN rising edge, not yet paused/aborted/finished
  bool inflight = false;
  bool discard = false;  // aborted while a transaction was on the line
  uint32_t packet = 0;
  Address master{};
  uint32_t length = 0;
  bool read = true;
  int phase = 0;  // MD2: 0 receiving, 1 waiting for the reply length, 2 replying
  uint64_t reply_since_us = 0;
};

struct ClinkState {
  std::shared_ptr<ClinkPorts> ports;
  std::map<uint32_t, Instance> instances;
};

constexpr uint32_t kReadyRelay[5] = {0, 1960, 1962, 1936, 1938};
constexpr uint32_t kFinishedRelay[5] = {0, 1961, 1963, 1937, 1939};

uint16_t reg(Memory& m, const Address& base, uint32_t k) {
  if (base.index + k >= area_size(base.area)) return 0;
  return uint16_t(m.read(Address{base.area, Width::Word, base.index + k}));
}
void set_reg(Memory& m, const Address& base, uint32_t k, uint16_t v) {
  if (base.index + k < area_size(base.area)) m.write(Address{base.area, Width::Word, base.index + k}, v);
}

}  // namespace

void add_clink_function(FunctionTable& table, std::shared_ptr<ClinkPorts> ports) {
  auto state = std::make_shared<ClinkState>();
  state->ports = std::move(ports);
  using R = OperandRole;
  FunctionSpec s;
  s.number = 151;
  s.mnemonic = "CLINK";
  s.inputs = {"EN", "PAU", "ABT"};
  s.operands = {{"Pt", R::Const}, {"MD", R::Const}, {"SR", R::Register}, {"WR", R::Register, false, 8},
                {"ACT", R::BitOut, true}, {"ERR", R::BitOut, true}, {"DN", R::BitOut, true}};
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;  // sees EN fall, and polls the line every scan
  s.handler = [state](ExecContext& c, const BoundOperand* o) {
    Memory& m = c.mem;
    const int pt = int(c.get(o[0]));
    const int md = int(c.get(o[1]));
    const Address sr = o[2].addr, wr = o[3].addr;
    const bool en = c.inputs[0], pau = c.inputs[1], abt = c.inputs[2];
    Instance& st = state->instances[c.instance];
    const bool rising = en && !st.prev_en;
    st.prev_en = en;
    c.flag(o[6], false);  // DN and ERR pulse for one scan per finished transaction
    c.flag(o[5], false);
    ClinkPorts::Port* port = state->ports ? state->ports->port(pt) : nullptr;
    bool finished_now = false;  // at most one transaction per scan: DN shows with its own WR
    bool failed = false;
    auto finish = [&](ClinkResult r, uint8_t station, uint8_t cmd) {
      finished_now = true;
      failed = r != ClinkResult::Ok;
      set_reg(m, wr, 0, uint16_t((uint16_t(r) << 8) | (st.packet & 0xFF)));
      if (md == 0) set_reg(m, wr, 1, uint16_t((station << 8) | cmd));
      c.flag(o[6], true);
      c.flag(o[5], failed);
      if (md != 0) return;
      const uint32_t count = reg(m, sr, 0) & 0xFF;
      if (++st.packet >= count) {
        st.packet = 0;
        m.set_bit(Area::M, kFinishedRelay[pt], true);
      }
    };
    auto store_received = [&](const std::string& in) {  // WR+8 count, WR+9.. one byte per word
      set_reg(m, wr, 8, uint16_t(in.size()));
      for (size_t i = 0; i < in.size(); ++i) set_reg(m, wr, 9 + uint32_t(i), uint8_t(in[i]));
    };
    auto raw_bytes = [&](uint32_t len) {
      std::string tx;
      for (uint32_t i = 0; i < len; ++i) tx.push_back(char(reg(m, sr, 3 + i) & 0xFF));
      return tx;
    };
    auto gap_ms = [&] {
      const uint32_t g = m.bit(Area::M, 1956) ? (m.read(Address{Area::R, Width::Word, 4148}) >> 8) : 0;
      return g ? int(g) : 12;  // R4148 high byte when M1956 = 1, else the 12 ms default
    };
    if (md > 2 || !port) {  // MD3, a bad mode, or an unconfigured port
      if (rising) {
        set_reg(m, wr, 0, uint16_t(uint16_t(ClinkResult::Command) << 8));
        c.flag(o[6], true);
        c.flag(o[5], true);
      }
      c.flag(o[4], false);
      return;
    }
    std::unique_lock<std::mutex> lk(port->mu);
    const int me = int(c.instance);
    if (port->com->holder() == me) m.set_bit(Area::M, kFinishedRelay[pt], false);
    if (abt) {  // abort now; restart from the first packet next time
      if (port->com->holder() == me) {
        if (st.inflight) {
          st.discard = true;
          port->cancel = true;
        }
        port->com->release();
      }
      st.active = false;
      st.packet = 0;
      st.phase = 0;
    } else if (rising && !pau) {
      st.active = true;
    }
    // A finished transaction: apply it (even when paused; discarded after an abort).
    if (st.inflight && port->done) {
      port->done = false;
      port->cancel = false;
      st.inflight = false;
      if (st.discard) {
        st.discard = false;
      } else if (md == 0) {
        ClinkResult r = port->result;
        if (r == ClinkResult::Ok && st.read) {
          if (port->rsp.values.size() != st.length) r = ClinkResult::BadData;
          else
            for (uint32_t i = 0; i < st.length; ++i) m.write(offset_address(st.master, i), port->rsp.values[i]);
        }
        finish(r, uint8_t(port->job.station), uint8_t(port->job.cmd));
      } else if (md == 1) {
        if (port->raw.rx) store_received(port->received);
        finish(port->result, 0, 0);
      } else {  // MD2: a message came in, or the reply went out
        if (st.phase == 0) {
          store_received(port->received);
          if (port->result == ClinkResult::Ok && (reg(m, sr, 0) & 0x01)) {
            st.phase = 1;  // reply when the program fills SR+2
            st.reply_since_us = c.now_us;
          }
        } else {
          set_reg(m, sr, 2, 0);  // plc_cell: the reply length is cleared once it is sent
          st.phase = 0;
        }
        finish(port->result, 0, 0);
      }
      if (pau || !en) {  // PAU or EN off: release the port after this transaction
        if (port->com->holder() == me) port->com->release();
        st.active = false;
        st.phase = 0;
      }
    }
    if (st.active && port->com->holder() < 0 && !st.inflight) port->com->hold(me);
    const bool own = port->com->holder() == me;
    auto submit_raw = [&](ClinkPorts::Port::Raw r) {
      port->raw_job = true;
      port->raw = std::move(r);
      port->done = false;
      port->cancel = false;
      port->has_job = true;
      st.inflight = true;
      port->post();
    };
    if (own && st.active && !st.inflight && !pau && !abt && !finished_now) {
      const uint16_t codes = reg(m, sr, 1);
      if (md == 0) {
        // Next packet: 7 words from SR+1+7*packet, validated before anything is sent.
        const uint32_t count = reg(m, sr, 0) & 0xFF;
        const uint32_t base = 1 + 7 * st.packet;
        const uint8_t station = uint8_t(reg(m, sr, base) & 0xFF);
        const uint32_t cmd = reg(m, sr, base + 1) & 0xFF, len = reg(m, sr, base + 2) & 0xFF;
        const uint32_t mtype = reg(m, sr, base + 3) & 0xFF, mref = reg(m, sr, base + 4);
        const uint32_t stype = reg(m, sr, base + 5) & 0xFF, sref = reg(m, sr, base + 6);
        Address ma, sa;
        ClinkResult bad = ClinkResult::Ok;
        if (count == 0) bad = ClinkResult::Length;
        else if (len == 0 || len > 64) bad = ClinkResult::Length;
        else if (cmd != 1 && cmd != 2) bad = ClinkResult::Command;
        else if (mtype > 13 || stype > 13) bad = ClinkResult::DataType;
        else if ((mtype <= 5) != (stype <= 5)) bad = ClinkResult::Inconsistent;
        else if (!data_address(mtype, mref, &ma) || !data_address(stype, sref, &sa)) bad = ClinkResult::Reference;
        else {
          try {
            check_span(ma, len);
            check_span(sa, len);
          } catch (const Error&) {
            bad = ClinkResult::Reference;
          }
        }
        const bool is_read = cmd == 1;
        const Cmd fcmd = stype <= 5 ? (is_read ? Cmd::ReadDiscretes : Cmd::WriteDiscretes)
                                    : (is_read ? Cmd::ReadRegisters : Cmd::WriteRegisters);
        if (bad != ClinkResult::Ok) {
          finish(bad, station, uint8_t(fcmd));
        } else if (station == 0 && is_read) {
          finish(ClinkResult::Command, station, uint8_t(fcmd));  // nobody answers a broadcast read
        } else {
          Request req;
          req.station = station;
          req.cmd = fcmd;
          req.start = sa;
          req.count = len;
          if (!is_read)
            for (uint32_t i = 0; i < len; ++i) req.values.push_back(m.read(offset_address(ma, i)));
          st.master = ma;
          st.length = len;
          st.read = is_read;
          port->client->set_station(station);
          port->raw_job = false;
          port->job = req;
          port->done = false;
          port->has_job = true;
          st.inflight = true;
          set_reg(m, wr, 1, uint16_t((station << 8) | uint8_t(fcmd)));
          port->post();
        }
      } else if (md == 1) {  // send SR+3.., then maybe receive
        const uint32_t len = reg(m, sr, 2);
        if (len == 0 || len > 511) {
          finish(ClinkResult::Length, 0, 0);
        } else {
          ClinkPorts::Port::Raw r;
          r.tx = raw_bytes(len);
          r.rx = (reg(m, sr, 0) & 0x01) != 0;
          r.start = uint8_t(codes >> 8);
          r.end = uint8_t(codes);
          r.gap_ms = gap_ms();
          r.timeout_ms = port->timeout_ms;
          submit_raw(r);
        }
      } else if (st.phase == 0) {  // MD2: wait for a message (until EN off, PAU or ABT)
        ClinkPorts::Port::Raw r;
        r.rx = true;
        r.start = uint8_t(codes >> 8);
        r.end = uint8_t(codes);
        r.gap_ms = gap_ms();
        r.timeout_ms = 0;
        submit_raw(r);
      } else {  // MD2: reply as soon as SR+2 becomes non-zero, within the time-out
        const uint32_t len = reg(m, sr, 2);
        if (len > 511) {
          st.phase = 0;
          finish(ClinkResult::Length, 0, 0);
        } else if (len > 0) {
          st.phase = 2;
          ClinkPorts::Port::Raw r;
          r.tx = raw_bytes(len);
          submit_raw(r);
        } else if (c.now_us - st.reply_since_us > uint64_t(port->timeout_ms) * 1000) {
          st.phase = 0;
          finish(ClinkResult::Timeout, 0, 0);
        }
      }
    }
    if (!en && own) {  // EN off: give the port back (a pending receive is cancelled first)
      if (st.inflight) {
        if (md == 2 && st.phase == 0) {
          st.discard = true;
          port->cancel = true;
        }
      } else {
        port->com->release();
        st.active = false;
        st.phase = 0;
      }
    }
    const bool own_now = port->com->holder() == me;
    set_reg(m, wr, 4, uint16_t((st.active && !own_now ? 1 : 0) | (own_now ? 1u << 12 : 0) |
                               (failed ? 1u << 13 : 0) | (finished_now ? 1u << 14 : 0)));
    m.set_bit(Area::M, kReadyRelay[pt], port->com->holder() < 0);
    c.flag(o[4], own_now);
  };
  table.add(s);
}

}  // namespace fatek
}  // namespace plc_cell
