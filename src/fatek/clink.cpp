#include "plc_cell/fatek/clink.h"

#include <condition_variable>
#include <map>
#include <mutex>
#include <thread>

#include "plc_cell/core/error.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {
namespace fatek {

// One line with one transaction at a time, run by its own thread.
struct ClinkPorts::Port {
  std::unique_ptr<Client> client;
  int owner = -1;  // instruction instance holding the port (the "port ready" relay is owner < 0)
  std::mutex mu;
  std::condition_variable cv;
  bool has_job = false, done = false, stop = false;
  Request job;
  Response rsp;
  ClinkResult result = ClinkResult::Ok;
  std::thread th;

  void run() {
    std::unique_lock<std::mutex> lk(mu);
    for (;;) {
      cv.wait(lk, [&] { return stop || has_job; });
      if (stop) return;
      Request req = job;
      lk.unlock();
      Response r;
      ClinkResult res = ClinkResult::Ok;
      try {
        r = client->transact(req);
      } catch (const PlcError&) {
        res = ClinkResult::BadData;  // the slave answered with an error code
      } catch (const CommError& e) {
        res = std::string(e.what()).find("no answer") != std::string::npos ? ClinkResult::Timeout : ClinkResult::BadData;
      } catch (const std::exception&) {
        res = ClinkResult::BadData;
      }
      lk.lock();
      rsp = std::move(r);
      result = res;
      has_job = false;
      done = true;
    }
  }
};

ClinkPorts::ClinkPorts() = default;

ClinkPorts::~ClinkPorts() {
  for (auto& p : ports_) {
    if (!p) continue;
    {
      std::lock_guard<std::mutex> lk(p->mu);
      p->stop = true;
    }
    p->cv.notify_all();
    if (p->th.joinable()) p->th.join();
  }
}

void ClinkPorts::set_port(int n, std::unique_ptr<Transport> t, int timeout_ms) {
  if (n < 1 || n > 4) throw Error("FUN151 port " + std::to_string(n) + " outside 1..4");
  auto p = std::make_unique<Port>();
  ClientOptions o;
  o.timeout_ms = timeout_ms;
  o.retries = 0;  // the ladder program decides about repeating
  p->client = std::make_unique<Client>(std::move(t), o);
  p->th = std::thread([q = p.get()] { q->run(); });
  ports_[size_t(n)] = std::move(p);
}

bool ClinkPorts::has(int n) const { return n >= 1 && n <= 4 && ports_[size_t(n)]; }
ClinkPorts::Port* ClinkPorts::port(int n) { return has(n) ? ports_[size_t(n)].get() : nullptr; }

std::shared_ptr<ClinkPorts> ClinkPorts::from_yaml(const YAML::Node& f) {
  auto ports = std::make_shared<ClinkPorts>();
  if (!f || !f["ports"]) return ports;
  const int timeout = f["timeout_ms"] ? f["timeout_ms"].as<int>() : 500;
  for (const auto& kv : f["ports"]) {
    const int n = kv.first.as<int>();
    const std::string where = kv.second.as<std::string>();
    if (where.rfind("tcp:", 0) == 0) ports->set_port(n, tcp_transport(where.substr(4)), timeout);
    else ports->set_port(n, serial_transport(parse_serial_settings(where, "7E1")), timeout);
  }
  return ports;
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
};

struct ClinkState {
  std::shared_ptr<ClinkPorts> ports;
  std::map<uint32_t, Instance> instances;
};

constexpr uint32_t kReadyRelay[5] = {0, 1960, 1962, 1936, 1938};
constexpr uint32_t kFinishedRelay[5] = {0, 1961, 1963, 1937, 1939};

uint16_t reg(Memory& m, const Address& base, uint32_t k) {
  return uint16_t(m.read(Address{base.area, Width::Word, base.index + k}));
}
void set_reg(Memory& m, const Address& base, uint32_t k, uint16_t v) {
  m.write(Address{base.area, Width::Word, base.index + k}, v);
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
    c.flag(o[6], false);  // DN and ERR pulse for one scan per finished packet
    c.flag(o[5], false);
    ClinkPorts::Port* port = state->ports ? state->ports->port(pt) : nullptr;
    bool finished_now = false;  // at most one packet per scan: DN shows with its own WR+1
    auto finish_packet = [&](ClinkResult r, uint8_t station, uint8_t cmd) {
      finished_now = true;
      set_reg(m, wr, 0, uint16_t((uint16_t(r) << 8) | (st.packet & 0xFF)));
      set_reg(m, wr, 1, uint16_t((station << 8) | cmd));
      c.flag(o[6], true);
      c.flag(o[5], r != ClinkResult::Ok);
      const uint32_t count = reg(m, sr, 0) & 0xFF;
      if (++st.packet >= count) {
        st.packet = 0;
        m.set_bit(Area::M, kFinishedRelay[pt], true);
      }
    };
    if (md != 0 || !port) {  // unsupported mode or an unconfigured port
      if (rising) {
        set_reg(m, wr, 0, uint16_t(uint16_t(ClinkResult::Command) << 8));
        c.flag(o[6], true);
        c.flag(o[5], true);
      }
      c.flag(o[4], false);
      return;
    }
    std::unique_lock<std::mutex> lk(port->mu);
    const bool mine = port->owner == int(c.instance);
    if (mine) m.set_bit(Area::M, kFinishedRelay[pt], false);
    if (abt) {  // abort now; restart from the first packet next time
      if (mine) {
        st.discard = st.inflight;
        port->owner = -1;
      }
      st.active = false;
      st.packet = 0;
    } else if (rising && !pau) {
      st.active = true;
    }
    // A finished transaction: apply it (even when paused; discarded after an abort).
    if (st.inflight && port->done) {
      port->done = false;
      st.inflight = false;
      if (st.discard) {
        st.discard = false;
      } else {
        ClinkResult r = port->result;
        if (r == ClinkResult::Ok && st.read) {
          if (port->rsp.values.size() != st.length) r = ClinkResult::BadData;
          else
            for (uint32_t i = 0; i < st.length; ++i) m.write(offset_address(st.master, i), port->rsp.values[i]);
        }
        finish_packet(r, uint8_t(port->job.station), uint8_t(port->job.cmd));
      }
      if (pau || !en) {  // PAU or EN off: release the port after this transaction
        port->owner = -1;
        st.active = false;
      }
    }
    if (st.active && port->owner < 0 && !st.inflight) port->owner = int(c.instance);
    const bool own = port->owner == int(c.instance);
    set_reg(m, wr, 4, uint16_t((st.active && !own ? 1 : 0) | (own ? 1u << 12 : 0)));
    if (own && st.active && !st.inflight && !pau && !abt && !finished_now) {
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
        finish_packet(bad, station, uint8_t(fcmd));
      } else if (station == 0 && is_read) {
        finish_packet(ClinkResult::Command, station, uint8_t(fcmd));  // nobody answers a broadcast read
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
        port->job = req;
        port->done = false;
        port->has_job = true;
        st.inflight = true;
        set_reg(m, wr, 1, uint16_t((station << 8) | uint8_t(fcmd)));
        port->cv.notify_all();
      }
    }
    if (!en && !st.inflight && own) {  // EN off between transactions: give the port back
      port->owner = -1;
      st.active = false;
    }
    m.set_bit(Area::M, kReadyRelay[pt], port->owner < 0);
    c.flag(o[4], port->owner == int(c.instance));
  };
  table.add(s);
}

}  // namespace fatek
}  // namespace plc_cell
