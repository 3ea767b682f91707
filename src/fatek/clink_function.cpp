// FUN151 CLINK, the instruction (manual ch. 13): each scan applies a finished transaction
// of its port and hands the port the next one. The ports are clink.cpp's.
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "clink_port.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/fatek/clink.h"

namespace plc_cell {
namespace fatek {

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

// One execution of the instruction: its operands and inputs, its instance, its port.
class Call {
 public:
  Call(ClinkState& state, ExecContext& c, const BoundOperand* o)
      : c_(c),
        m_(c.mem),
        o_(o),
        pt_(int(c.get(o[0]))),
        md_(int(c.get(o[1]))),
        sr_(o[2].addr),
        wr_(o[3].addr),
        en_(c.inputs[0]),
        pau_(c.inputs[1]),
        abt_(c.inputs[2]),
        st_(state.instances[c.instance]),
        port_(state.ports ? state.ports->port(pt_) : nullptr),
        me_(int(c.instance)) {}

  void run() {
    const bool rising = en_ && !st_.prev_en;
    st_.prev_en = en_;
    c_.flag(o_[6], false);  // DN and ERR pulse for one scan per finished transaction
    c_.flag(o_[5], false);
    if (md_ > 2 || !port_) {  // MD3, a bad mode, or an unconfigured port
      if (rising) {
        set_reg(m_, wr_, 0, uint16_t(uint16_t(ClinkResult::Command) << 8));
        c_.flag(o_[6], true);
        c_.flag(o_[5], true);
      }
      c_.flag(o_[4], false);
      return;
    }
    std::unique_lock<std::mutex> lk(port_->mu);
    if (port_->com->holder() == me_) m_.set_bit(Area::M, kFinishedRelay[pt_], false);
    if (abt_) abort();
    else if (rising && !pau_) st_.active = true;
    // A finished transaction: apply it (even when paused; discarded after an abort).
    if (st_.inflight && port_->done) apply_finished();
    if (st_.active && port_->com->holder() < 0 && !st_.inflight) port_->com->hold(me_);
    const bool own = port_->com->holder() == me_;
    if (own && st_.active && !st_.inflight && !pau_ && !abt_ && !finished_now_) {
      if (md_ == 0) next_packet();
      else if (md_ == 1) next_send();
      else next_md2();
    }
    if (!en_ && own) give_back();
    const bool own_now = port_->com->holder() == me_;
    set_reg(m_, wr_, 4, uint16_t((st_.active && !own_now ? 1 : 0) | (own_now ? 1u << 12 : 0) |
                                 (failed_ ? 1u << 13 : 0) | (finished_now_ ? 1u << 14 : 0)));
    m_.set_bit(Area::M, kReadyRelay[pt_], port_->com->holder() < 0);
    c_.flag(o_[4], own_now);
  }

 private:
  // At most one transaction per scan: DN shows with its own WR.
  void finish(ClinkResult r, uint8_t station, uint8_t cmd) {
    finished_now_ = true;
    failed_ = r != ClinkResult::Ok;
    set_reg(m_, wr_, 0, uint16_t((uint16_t(r) << 8) | (st_.packet & 0xFF)));
    if (md_ == 0) set_reg(m_, wr_, 1, uint16_t((station << 8) | cmd));
    c_.flag(o_[6], true);
    c_.flag(o_[5], failed_);
    if (md_ != 0) return;
    const uint32_t count = reg(m_, sr_, 0) & 0xFF;
    if (++st_.packet >= count) {
      st_.packet = 0;
      m_.set_bit(Area::M, kFinishedRelay[pt_], true);
    }
  }
  void store_received(const std::string& in) {  // WR+8 count, WR+9.. one byte per word
    set_reg(m_, wr_, 8, uint16_t(in.size()));
    for (size_t i = 0; i < in.size(); ++i) set_reg(m_, wr_, 9 + uint32_t(i), uint8_t(in[i]));
  }
  std::string raw_bytes(uint32_t len) {
    std::string tx;
    for (uint32_t i = 0; i < len; ++i) tx.push_back(char(reg(m_, sr_, 3 + i) & 0xFF));
    return tx;
  }
  int gap_ms() {
    const uint32_t g = m_.bit(Area::M, 1956) ? (m_.read(Address{Area::R, Width::Word, 4148}) >> 8) : 0;
    return g ? int(g) : 12;  // R4148 high byte when M1956 = 1, else the 12 ms default
  }

  // ABT: abort now; restart from the first packet next time.
  void abort() {
    if (port_->com->holder() == me_) {
      if (st_.inflight) {
        st_.discard = true;
        port_->cancel = true;
      }
      port_->com->release();
    }
    st_.active = false;
    st_.packet = 0;
    st_.phase = 0;
  }

  void apply_finished() {
    port_->done = false;
    port_->cancel = false;
    st_.inflight = false;
    if (st_.discard) {
      st_.discard = false;
    } else if (md_ == 0) {
      ClinkResult r = port_->result;
      if (r == ClinkResult::Ok && st_.read) {
        if (port_->rsp.values.size() != st_.length) r = ClinkResult::BadData;
        else
          for (uint32_t i = 0; i < st_.length; ++i) m_.write(offset_address(st_.master, i), port_->rsp.values[i]);
      }
      finish(r, uint8_t(port_->job.station), uint8_t(port_->job.cmd));
    } else if (md_ == 1) {
      if (port_->raw.rx) store_received(port_->received);
      finish(port_->result, 0, 0);
    } else {  // MD2: a message came in, or the reply went out
      if (st_.phase == 0) {
        store_received(port_->received);
        if (port_->result == ClinkResult::Ok && (reg(m_, sr_, 0) & 0x01)) {
          st_.phase = 1;  // reply when the program fills SR+2
          st_.reply_since_us = c_.now_us;
        }
      } else {
        set_reg(m_, sr_, 2, 0);  // plc_cell: the reply length is cleared once it is sent
        st_.phase = 0;
      }
      finish(port_->result, 0, 0);
    }
    if (pau_ || !en_) {  // PAU or EN off: release the port after this transaction
      if (port_->com->holder() == me_) port_->com->release();
      st_.active = false;
      st_.phase = 0;
    }
  }

  void submit_raw(ClinkPorts::Port::Raw r) {
    port_->raw_job = true;
    port_->raw = std::move(r);
    port_->done = false;
    port_->cancel = false;
    port_->has_job = true;
    st_.inflight = true;
    port_->post();
  }

  // MD0: the next packet, 7 words from SR+1+7*packet, validated before anything is sent.
  void next_packet() {
    const uint32_t count = reg(m_, sr_, 0) & 0xFF;
    const uint32_t base = 1 + 7 * st_.packet;
    const uint8_t station = uint8_t(reg(m_, sr_, base) & 0xFF);
    const uint32_t cmd = reg(m_, sr_, base + 1) & 0xFF, len = reg(m_, sr_, base + 2) & 0xFF;
    const uint32_t mtype = reg(m_, sr_, base + 3) & 0xFF, mref = reg(m_, sr_, base + 4);
    const uint32_t stype = reg(m_, sr_, base + 5) & 0xFF, sref = reg(m_, sr_, base + 6);
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
    if (bad != ClinkResult::Ok) return finish(bad, station, uint8_t(fcmd));
    if (station == 0 && is_read) return finish(ClinkResult::Command, station, uint8_t(fcmd));  // nobody answers a broadcast read
    Request req;
    req.station = station;
    req.cmd = fcmd;
    req.start = sa;
    req.count = len;
    if (!is_read)
      for (uint32_t i = 0; i < len; ++i) req.values.push_back(m_.read(offset_address(ma, i)));
    st_.master = ma;
    st_.length = len;
    st_.read = is_read;
    port_->client->set_station(station);
    port_->raw_job = false;
    port_->job = req;
    port_->done = false;
    port_->has_job = true;
    st_.inflight = true;
    set_reg(m_, wr_, 1, uint16_t((station << 8) | uint8_t(fcmd)));
    port_->post();
  }

  // MD1: send SR+3.., then maybe receive.
  void next_send() {
    const uint16_t codes = reg(m_, sr_, 1);
    const uint32_t len = reg(m_, sr_, 2);
    if (len == 0 || len > 511) return finish(ClinkResult::Length, 0, 0);
    ClinkPorts::Port::Raw r;
    r.tx = raw_bytes(len);
    r.rx = (reg(m_, sr_, 0) & 0x01) != 0;
    r.start = uint8_t(codes >> 8);
    r.end = uint8_t(codes);
    r.gap_ms = gap_ms();
    r.timeout_ms = port_->timeout_ms;
    submit_raw(r);
  }

  void next_md2() {
    const uint16_t codes = reg(m_, sr_, 1);
    if (st_.phase == 0) {  // wait for a message (until EN off, PAU or ABT)
      ClinkPorts::Port::Raw r;
      r.rx = true;
      r.start = uint8_t(codes >> 8);
      r.end = uint8_t(codes);
      r.gap_ms = gap_ms();
      r.timeout_ms = 0;
      return submit_raw(r);
    }
    // Reply as soon as SR+2 becomes non-zero, within the time-out.
    const uint32_t len = reg(m_, sr_, 2);
    if (len > 511) {
      st_.phase = 0;
      finish(ClinkResult::Length, 0, 0);
    } else if (len > 0) {
      st_.phase = 2;
      ClinkPorts::Port::Raw r;
      r.tx = raw_bytes(len);
      submit_raw(r);
    } else if (c_.now_us - st_.reply_since_us > uint64_t(port_->timeout_ms) * 1000) {
      st_.phase = 0;
      finish(ClinkResult::Timeout, 0, 0);
    }
  }

  // EN off: give the port back (a pending receive is cancelled first).
  void give_back() {
    if (st_.inflight) {
      if (md_ == 2 && st_.phase == 0) {
        st_.discard = true;
        port_->cancel = true;
      }
      return;
    }
    port_->com->release();
    st_.active = false;
    st_.phase = 0;
  }

  ExecContext& c_;
  Memory& m_;
  const BoundOperand* o_;
  const int pt_, md_;
  const Address sr_, wr_;
  const bool en_, pau_, abt_;
  Instance& st_;
  ClinkPorts::Port* port_;
  const int me_;
  bool finished_now_ = false, failed_ = false;
};

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
  s.handler = [state](ExecContext& c, const BoundOperand* o) { Call(*state, c, o).run(); };
  table.add(s);
}

}  // namespace fatek
}  // namespace plc_cell
