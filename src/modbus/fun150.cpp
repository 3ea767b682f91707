#include "plc_cell/modbus/fun150.h"

#include <atomic>
#include <cerrno>
#include <climits>
#include <condition_variable>
#include <mutex>
#include <vector>

#include <modbus/modbus.h>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace modbus {

using namespace mbus_result;

std::map<int, MbusPort> parse_mbus_ports(const YAML::Node& section, const std::string& file) {
  std::map<int, MbusPort> out;
  if (!section) return out;
  const YamlReader r(file);
  r.only(section, "modbus", {"ports"});
  const YAML::Node ports = section["ports"];
  if (!ports) return out;
  if (!ports.IsMap()) r.fail(ports, "modbus.ports", "expected a mapping of ports 1..4 to {tcp: HOST:PORT} or {rtu: DEVICE}");
  for (const auto& kv : ports) {
    const std::string k = "modbus.ports." + r.str(kv.first, "modbus.ports");
    const int n = r.integer(kv.first, k, INT_MIN, INT_MAX);
    if (n < 1 || n > 4) r.fail(kv.first, k, "port " + std::to_string(n) + " (FUN150 uses ports 1..4)");
    r.only(kv.second, k, {"tcp", "rtu"});
    MbusPort p;
    if (kv.second["tcp"]) p.tcp = r.host_port(kv.second["tcp"], k + ".tcp");
    if (kv.second["rtu"]) p.rtu = r.serial_line(kv.second["rtu"], k + ".rtu", "8E1");
    if (kv.second["tcp"].IsDefined() == kv.second["rtu"].IsDefined()) r.fail(kv.second, k, "give one of tcp or rtu");
    out[n] = p;
  }
  return out;
}

namespace {

// Port interface relays and time-out registers [M:4800-4830].
constexpr uint32_t kReadyRelay[5] = {0, 1960, 1962, 1936, 1938};
constexpr uint32_t kFinishedRelay[5] = {0, 1961, 1963, 1937, 1939};
constexpr uint32_t kTimeoutReg[5] = {0, 4147, 4159, 4045, 4048};

struct Job {
  int station = 0, fc = 0;
  uint32_t address = 0, count = 0;
  // Where read data goes in the PLC, fixed (and checked) when the job is submitted: the
  // program may rewrite its table while the transaction is on the line.
  Area master_area = Area::R;
  uint32_t master_start = 0;
  std::vector<uint16_t> data;  // write data in, read data out (bits as 0/1)
  int timeout_ms = 500;
  int result = kOk;
};

// FUN150's use of one COM port: a libmodbus context for the framing, on the port's own
// line (the port opens and reopens it; libmodbus never connects or closes it), and one
// transaction at a time on the port's thread, shared with FUN151.
class PortWorker {
 public:
  explicit PortWorker(std::shared_ptr<ComPort> port) : port_(std::move(port)) {}
  // Waits for a transaction of ours still queued or on the line: the port's thread must
  // not run it once we are gone (the port may outlive us, shared with FUN151).
  ~PortWorker() {
    std::unique_lock<std::mutex> lk(mu_);
    stop_ = true;
    cv_.wait(lk, [&] { return !pending_; });
    if (ctx_) modbus_free(ctx_);
  }
  ComPort& port() { return *port_; }
  bool idle() {
    std::lock_guard<std::mutex> lk(mu_);
    return !pending_ && !done_;
  }
  void submit(Job j) {
    {
      std::lock_guard<std::mutex> lk(mu_);
      job_ = std::move(j);
      pending_ = true;
    }
    port_->submit([this] { run_one(); });
  }
  bool take(Job* out) {  // the finished job, if any
    std::lock_guard<std::mutex> lk(mu_);
    if (!done_) return false;
    *out = std::move(job_);
    done_ = false;
    return true;
  }
  void discard() {  // ABT: a result still to come is dropped
    std::lock_guard<std::mutex> lk(mu_);
    if (pending_) discard_ = true;
    done_ = false;
  }

 private:
  bool connect() {
    const ComLine& line = port_->line();
    if (!ctx_) {
      if (line.is_tcp()) {
        std::string host;
        int port;
        parse_host_port(line.tcp, &host, &port);
        ctx_ = modbus_new_tcp(host.empty() ? "127.0.0.1" : host.c_str(), port);
      } else {
        const SerialSettings& s = line.serial;
        ctx_ = modbus_new_rtu(s.device.c_str(), s.baud, s.parity, s.data_bits, s.stop_bits);
      }
      if (!ctx_) return false;
    }
    const int fd = port_->fd();
    if (fd < 0) return false;
    modbus_set_socket(ctx_, fd);
    return true;
  }

  void execute(Job& j) {
    if (!connect()) {
      j.result = kNoResponse;
      return;
    }
    modbus_set_slave(ctx_, j.station);
    modbus_set_response_timeout(ctx_, uint32_t(j.timeout_ms / 1000), uint32_t(j.timeout_ms % 1000) * 1000);
    int rc = -1;
    const int n = int(j.count);
    std::vector<uint8_t> bits(j.count);
    switch (j.fc) {
      case 1: rc = modbus_read_bits(ctx_, int(j.address), n, bits.data()); break;
      case 2: rc = modbus_read_input_bits(ctx_, int(j.address), n, bits.data()); break;
      case 3: rc = modbus_read_registers(ctx_, int(j.address), n, j.data.data()); break;
      case 4: rc = modbus_read_input_registers(ctx_, int(j.address), n, j.data.data()); break;
      case 5: rc = modbus_write_bit(ctx_, int(j.address), j.data[0] ? 1 : 0) == 1 ? 1 : -1; break;
      case 6: rc = modbus_write_register(ctx_, int(j.address), j.data[0]) == 1 ? 1 : -1; break;
      case 15:
        for (uint32_t i = 0; i < j.count; ++i) bits[i] = uint8_t(j.data[i] != 0);
        rc = modbus_write_bits(ctx_, int(j.address), n, bits.data());
        break;
      case 16: rc = modbus_write_registers(ctx_, int(j.address), n, j.data.data()); break;
    }
    if (j.fc == 1 || j.fc == 2)
      for (uint32_t i = 0; i < j.count; ++i) j.data[i] = bits[i];
    const bool broadcast = j.station == 0;
    if (rc >= 0 || (broadcast && errno == ETIMEDOUT)) {  // broadcast: slaves do not reply
      j.result = kOk;
    } else if (errno == ETIMEDOUT) {
      j.result = kNoResponse;
      // A late reply carries the station and function of the next request too: no byte of
      // it may be taken for one (io/com_port.h).
      port_->resynchronise(j.timeout_ms);
      modbus_flush(ctx_);
    } else {
      j.result = kCommError;  // bad data or an exception reply
      const int err = errno;
      if (err < MODBUS_ENOBASE) port_->lost(modbus_strerror(err));  // the line itself failed
      else if (err > MODBUS_ENOBASE + 11) port_->resynchronise(j.timeout_ms);  // garbled: its rest may follow
    }
  }

  void run_one() {
    Job j;
    {
      std::unique_lock<std::mutex> lk(mu_);
      if (stop_) {
        pending_ = false;
        cv_.notify_all();
        return;
      }
      j = job_;
    }
    execute(j);
    std::lock_guard<std::mutex> lk(mu_);
    pending_ = false;
    cv_.notify_all();
    if (discard_) {
      discard_ = false;
      return;
    }
    job_ = std::move(j);
    done_ = true;
  }

  std::shared_ptr<ComPort> port_;
  modbus_t* ctx_ = nullptr;
  std::mutex mu_;
  std::condition_variable cv_;
  Job job_;
  bool pending_ = false, done_ = false, discard_ = false, stop_ = false;
};

struct Instance {
  bool last_en = false;
  bool running = false;
  bool in_flight = false;
  bool error = false;
  bool done = false;
  bool started_once = false;
  int port = 0;
  uint32_t tx = 0, n_tx = 0;
};

// One transaction of the table, decoded and checked.
struct Tx {
  int station, cmd, len, mtype, mstart, stype;
  uint32_t sref;
};

bool master_range(int type, Area* area, uint32_t* max) {
  switch (type) {
    case 1: *area = Area::Y; *max = 255; return true;
    case 2: *area = Area::M; *max = 1911; return true;
    case 3: *area = Area::S; *max = 999; return true;
    case 12: *area = Area::R; *max = 3839; return true;
    case 13: *area = Area::D; *max = 3999; return true;
    default: return false;
  }
}

// Checks a transaction in the manual's order; returns a result code, and the FC.
int check(const Tx& t, int* fc) {
  if (t.cmd < 1 || t.cmd > 3) return kCommand;
  const bool bits = t.mtype >= 1 && t.mtype <= 3;
  if (t.len < 1 || t.len > (bits ? 255 : 125)) return kLength;
  Area a;
  uint32_t max;
  if (!master_range(t.mtype, &a, &max)) return kDataType;
  if (t.stype != 0 && t.stype != 1 && t.stype != 3 && t.stype != 4) return kDataType;
  if (uint32_t(t.mstart) + uint32_t(t.len) - 1 > max || t.sref < 1 || t.sref + uint32_t(t.len) - 1 > 65536)
    return kReference;
  const bool sbits = t.stype == 0 || t.stype == 1;
  if (bits != sbits) return kInconsistent;  // bit types 1~3 with 0x/1x, words 12~13 with 3x/4x (spec §5 item 11)
  if (t.cmd != 1 && (t.stype == 1 || t.stype == 3)) return kInconsistent;  // inputs cannot be written
  if (t.station < 0 || t.station > 247 || (t.station == 0 && t.cmd == 1)) return kReference;
  static const int read_fc[5] = {1, 2, 0, 4, 3};
  *fc = t.cmd == 1 ? read_fc[t.stype] : t.cmd == 2 ? (sbits ? 15 : 16) : (sbits ? 5 : 6);
  return kOk;
}

}  // namespace

// One execution of FUN150: its operands, its instance's state and the WR registers.
struct MbusCall {
  ExecContext& c;
  const BoundOperand* o;
  Instance& s;
  uint16_t* wr;
  Address sr;
  uint32_t sr_room;
  void result(int code, uint32_t tx, int station, int fc) const {
    wr[0] = uint16_t(code << 8 | (tx & 0xFF));
    wr[1] = uint16_t((station & 0xFF) << 8 | (fc & 0xFF));
  }
  uint16_t table(uint32_t k) const { return k < sr_room ? c.mem.reg(sr.area, sr.index + k) : uint16_t(0); }
};

class MbusEngine {
 public:
  explicit MbusEngine(const ComPorts& ports) {
    for (const int n : ports.numbers()) workers_[n] = std::make_unique<PortWorker>(ports.get(n));
  }
  void exec(ExecContext& c, const BoundOperand* o);

 private:
  void finish(ExecContext& c, Instance& s);
  void start_pass(MbusCall& k, PortWorker* w, int port, bool ascii);
  void apply(MbusCall& k, PortWorker& w);
  void submit_next(MbusCall& k, PortWorker& w, int port);
  std::map<int, std::unique_ptr<PortWorker>> workers_;
  std::map<uint32_t, Instance> inst_;
};

void MbusEngine::finish(ExecContext& c, Instance& s) {
  s.running = s.in_flight = false;
  s.done = true;
  const auto w = workers_.find(s.port);
  if (w != workers_.end() && w->second->port().holder() == int(c.instance)) w->second->port().release();
  if (s.port >= 1 && s.port <= 4) c.mem.set_bit(Area::M, kFinishedRelay[s.port], true);
}

// EN rose: a pass over the table starts if the port is there, free and the table sound.
void MbusEngine::start_pass(MbusCall& k, PortWorker* w, int port, bool ascii) {
  Instance& s = k.s;
  s.port = port;
  s.error = s.done = false;
  if (!w || ascii) {  // no such port configured, or Modbus ASCII (no libmodbus backend)
    k.result(kPort, 0, 0, 0);
    s.error = s.done = true;
  } else if (w->port().holder() >= 0) {  // FUN151 or another FUN150 holds it
    k.wr[4] |= 0x0001;  // waiting for the port
    s.last_en = false;  // try again next scan, as if EN rose then
  } else if (k.table(0) != 0xA550 || (k.table(1) >> 8) != 0x07 || (k.table(1) & 0xFF) == 0 ||
             2 + 7 * uint32_t(k.table(1) & 0xFF) > k.sr_room) {
    k.result(kTable, 0, 0, 0);
    s.error = s.done = true;
  } else {
    w->port().hold(int(k.c.instance));
    s.running = true;
    s.tx = 0;
    s.n_tx = k.table(1) & 0xFF;
    k.wr[4] &= uint16_t(~0x0001);
  }
}

// The finished transaction, if any, into the PLC.
void MbusEngine::apply(MbusCall& k, PortWorker& w) {
  Job j;
  if (!k.s.in_flight || !w.take(&j)) return;
  k.s.in_flight = false;
  const Area a = j.master_area;
  if (j.result == kOk && (j.fc >= 1 && j.fc <= 4)) {
    for (uint32_t i = 0; i < j.count; ++i) {
      if (is_discrete(a)) k.c.mem.set_bit(a, j.master_start + i, j.data[i] != 0);
      else k.c.mem.set_reg(a, j.master_start + i, j.data[i]);
    }
  }
  k.result(j.result, k.s.tx, j.station, j.fc);
  if (j.result != kOk) k.s.error = true;
  if (++k.s.tx >= k.s.n_tx) finish(k.c, k.s);
}

// The next transaction of the table, checked, handed to the port.
void MbusEngine::submit_next(MbusCall& k, PortWorker& w, int port) {
  Instance& s = k.s;
  const uint32_t b = 2 + 7 * s.tx;
  const Tx t{int(k.table(b) & 0xFF), int(k.table(b + 1)), int(k.table(b + 2)), int(k.table(b + 3)),
             int(k.table(b + 4)), int(k.table(b + 5)), k.table(b + 6)};
  int fc = 0;
  const int code = check(t, &fc);
  if (code != kOk) {
    k.result(code, s.tx, t.station, 0);
    s.error = true;
    if (++s.tx >= s.n_tx) finish(k.c, s);
    return;
  }
  Area a = Area::R;  // check() above accepted t.mtype
  uint32_t max = 0;
  master_range(t.mtype, &a, &max);
  Job nj;
  nj.station = t.station;
  nj.fc = fc;
  nj.address = t.sref - 1;  // references are 1-based (spec §5 item 11)
  nj.count = (fc == 5 || fc == 6) ? 1 : uint32_t(t.len);
  nj.master_area = a;
  nj.master_start = uint32_t(t.mstart);
  nj.data.resize(nj.count);
  Memory& m = k.c.mem;
  if (fc == 5 || fc == 6 || fc == 15 || fc == 16)  // write data taken now, in this scan
    for (uint32_t i = 0; i < nj.count; ++i)
      nj.data[i] = is_discrete(a) ? uint16_t(m.bit(a, uint32_t(t.mstart) + i)) : m.reg(a, uint32_t(t.mstart) + i);
  const uint16_t to = m.reg(Area::R, kTimeoutReg[port]) & 0xFF;  // low byte, 0.01 s
  nj.timeout_ms = to ? to * 10 : 500;
  k.result(kOk, s.tx, t.station, fc);
  w.submit(std::move(nj));
  s.in_flight = true;
}

void MbusEngine::exec(ExecContext& c, const BoundOperand* o) {
  Instance& s = inst_[c.instance];
  const bool en = c.inputs[0], ascii = c.inputs[1], abort = c.inputs[2];
  const bool rising = en && !s.last_en;
  s.last_en = en;
  const int port = int(c.get(o[0]));
  const Address sr = o[1].addr, wra = o[2].addr;
  const uint32_t wr_room = area_size(wra.area) - wra.index;
  if (wr_room < 8) return;  // the parser checked the register; WR needs 8 of them
  MbusCall k{c, o, s, c.mem.words(wra.area) + wra.index, sr, area_size(sr.area) - sr.index};
  uint16_t* wr = k.wr;

  PortWorker* w = workers_.count(port) ? workers_[port].get() : nullptr;
  if (port >= 1 && port <= 4) {
    c.mem.set_bit(Area::M, kFinishedRelay[port], false);  // on for one scan after a pass
    c.mem.set_bit(Area::M, kReadyRelay[port], !w || w->port().holder() < 0);
  }
  if (abort && s.running) {  // release the port at once; a reply still to come is dropped
    if (w) w->discard();
    s.running = s.in_flight = false;
    if (w && w->port().holder() == int(c.instance)) w->port().release();
  }
  if (rising && !abort && !s.running) start_pass(k, w, port, ascii);
  if (s.running && w) {
    apply(k, *w);
    if (s.running && !s.in_flight) submit_next(k, *w, port);
  }

  const bool act = s.running;
  wr[4] = uint16_t((wr[4] & ~0x7000) | (act ? 0x1000 : 0) | (s.done && s.error ? 0x2000 : 0) | (s.done ? 0x4000 : 0));
  if (s.started_once || s.running) wr[4] |= 0x0010;  // not the first run
  s.started_once = s.started_once || s.running;
  c.flag(o[3], act);
  c.flag(o[4], s.done && s.error);
  c.flag(o[5], s.done);
}

ComLine mbus_line(const MbusPort& p) {
  ComLine l;
  if (!p.tcp.empty()) l.tcp = p.tcp;
  else l.serial = parse_serial_settings(p.rtu, "8E1");
  return l;
}

std::shared_ptr<MbusEngine> add_fun150(FunctionTable& t, std::map<int, MbusPort> ports) {
  std::map<int, ComLine> lines;
  for (const auto& p : ports) lines[p.first] = mbus_line(p.second);
  return add_fun150_on(t, ComPorts(lines));
}

std::shared_ptr<MbusEngine> add_fun150_on(FunctionTable& t, const ComPorts& ports) {
  auto engine = std::make_shared<MbusEngine>(ports);
  FunctionSpec s;
  s.number = 150;
  s.mnemonic = "MBUS";
  s.inputs = {"EN", "A/R", "ABT"};
  using R = OperandRole;
  s.operands = {{"Pt", R::Const}, {"SR", R::Register}, {"WR", R::Register},
                {"ACT", R::BitOut, true}, {"ERR", R::BitOut, true}, {"DN", R::BitOut, true}};
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;  // it watches EN rise and ABT while a pass runs
  MbusEngine* e = engine.get();
  s.handler = [e](ExecContext& c, const BoundOperand* o) { e->exec(c, o); };
  t.add(s);
  return engine;
}

}  // namespace modbus
}  // namespace plc_cell
