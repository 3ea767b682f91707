// FUN calls on both engines (docs/native-engine.md, "FUN calls"): the word forms equal the
// general handlers they come from, both engines choose the same form for the same operands,
// and a handler that throws stops both engines with the same runtime fault.
#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "plc_cell/core/plc.h"

#include "two_engines.h"

using namespace plc_cell;

namespace {

struct Rng {
  uint64_t s;
  uint32_t next() { return static_cast<uint32_t>((s = s * 6364136223846793005ull + 1442695040888963407ull) >> 33); }
  uint16_t word() {  // the edges of the ranges often, else anything
    static const uint16_t edges[] = {0, 1, 0x7FFF, 0x8000, 0xFFFF, 0xFFFE, 9, 16, 17, 33};
    return next() % 3 == 0 ? edges[next() % 10] : static_cast<uint16_t>(next());
  }
};

// One trial of FUN spec in the given width: the same random operands bound twice, once as
// ExecContext's BoundOperands over memory a, once as word-form pointers over memory b.
struct Trial {
  Memory a, b;
  std::vector<BoundOperand> bound;
  std::array<void*, 6> ptrs{};
  std::array<std::array<uint16_t, 2>, 6> consts{};

  Trial(const FunctionSpec& spec, bool is32, Rng& r) {
    for (uint32_t i = 0; i < 8; ++i) {
      const uint16_t w = r.word();
      const bool on = r.next() % 2, off = r.next() % 4 == 0;
      for (Memory* m : {&a, &b}) {
        m->set_reg(Area::R, i, w);
        m->set_bit(Area::M, i, on);
        m->set_disabled(Area::M, i, off);
      }
    }
    for (size_t k = 0; k < spec.operands.size(); ++k) add(spec.operands[k].role, is32, k, r);
  }
  void add(OperandRole role, bool is32, size_t k, Rng& r) {
    BoundOperand o;
    o.present = true;
    if (role == OperandRole::BitOut) {
      o.kind = Operand::Kind::Bit;
      o.present = r.next() % 3 != 0;
      const uint32_t i = r.next() % 8;
      if (o.present) o.b = a.bits(Area::M) + i;
      ptrs[k] = o.present ? b.bits(Area::M) + i : nullptr;
    } else if (role == OperandRole::Source && r.next() % 2) {
      o.kind = Operand::Kind::Const;
      const uint32_t raw = uint32_t(r.word()) | (is32 ? uint32_t(r.word()) << 16 : 0);
      o.k = is32 ? int64_t(int32_t(raw)) : int64_t(int16_t(raw));
      consts[k] = {static_cast<uint16_t>(raw), static_cast<uint16_t>(raw >> 16)};
      ptrs[k] = consts[k].data();
    } else {  // registers overlap at times, as R0 and R1 of two 32-bit operands do
      o.kind = is32 ? Operand::Kind::Reg32 : Operand::Kind::Reg16;
      const uint32_t i = r.next() % 6;
      o.w = a.words(Area::R) + i;
      ptrs[k] = b.words(Area::R) + i;
    }
    bound.push_back(o);
  }
  std::string difference() const {
    for (uint32_t i = 0; i < 8; ++i) {
      if (a.reg(Area::R, i) != b.reg(Area::R, i))
        return "R" + std::to_string(i) + ": " + std::to_string(a.reg(Area::R, i)) + " / " +
               std::to_string(b.reg(Area::R, i));
      if (a.bits(Area::M)[i] != b.bits(Area::M)[i]) return "M" + std::to_string(i);
    }
    return "";
  }
};

}  // namespace

TEST(NativeFunForms, EveryWordFormEqualsItsHandler) {
  const FunctionTable table = FunctionTable::with_core_functions();
  int forms = 0;
  Rng r{7};
  for (const FunctionSpec& spec : table.all()) {
    for (const bool is32 : {false, true}) {
      const WordHandler h = is32 ? spec.words.w32 : spec.words.w16;
      if (!h) continue;
      ++forms;
      for (int t = 0; t < 3000; ++t) {
        Trial x(spec, is32, r);
        ExecContext c(x.a);
        c.is32 = is32;
        c.en = true;
        c.inputs[0] = true;
        spec.handler(c, x.bound.data());
        h(x.ptrs[0], x.ptrs[1], x.ptrs[2], x.ptrs[3], x.ptrs[4], x.ptrs[5]);
        ASSERT_EQ(x.difference(), "") << spec.mnemonic << (is32 ? ".D" : "") << " trial " << t;
      }
    }
  }
  // MOV, MOVN, ADD, SUB, INC, DEC, CMP, WAND, WOR, WXOR, BCD, BIN, SHL, SHR in two widths.
  EXPECT_EQ(forms, 28);
}

namespace {

// PROBE: a FUN whose handler and word form write different values, so that the memory
// shows which one ran; THROW: a FUN whose handler throws while EN is on.
FunctionTable probe_table() {
  FunctionTable t = FunctionTable::with_core_functions();
  FunctionSpec s;
  s.number = 251;
  s.mnemonic = "PROBE";
  s.operands = {{"S", OperandRole::Source}, {"D", OperandRole::Dest}};
  s.handler = [](ExecContext& c, const BoundOperand* o) { c.put(o[1], c.get(o[1]) + 1); };
  s.words.w16 = [](void*, void* d, void*, void*, void*, void*) noexcept { *static_cast<uint16_t*>(d) += 100; };
  t.add(s);
  s = {};
  s.number = 252;
  s.mnemonic = "THROW";
  s.operands = {{"D", OperandRole::Dest}};
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    if (c.get(o[0]) == 3) throw 3;  // not a std::exception
    throw std::runtime_error("table full");
  };
  t.add(s);
  return t;
}

// Both engines on this file's table; every scan's results and faults must agree.
struct FormEngines : native_test::TwoEngines {
  explicit FormEngines(const std::string& text) : TwoEngines(table(), text, "forms.il") {}
  static const FunctionTable& table() {
    static const FunctionTable t = probe_table();
    return t;
  }
  bool scan() {
    bool ok = false;
    EXPECT_EQ(step(0, false, "the scan", &ok), "");
    return ok;
  }
};

}  // namespace

TEST(NativeFunForms, BothEnginesTakeTheWordFormWhereTheOperandsAllowIt) {
  FormEngines e(
      "ORG M1925\nPROBE S=R0 D=R1\nPROBE S=5 D=R2\nPROBE S=WX0 D=R3\nPROBE S=40000 D=R4\n"
      "PROBE.P S=R0 D=R5\nOUT Y0\nEND\n");
  ASSERT_TRUE(e.native.native_active()) << e.native.engine_status();
  EXPECT_TRUE(e.scan());
  EXPECT_EQ(e.mem_n.reg(Area::R, 1), 100u);  // registers and a constant in range: the word form
  EXPECT_EQ(e.mem_n.reg(Area::R, 2), 100u);
  EXPECT_EQ(e.mem_n.reg(Area::R, 3), 1u);    // a bit view: the handler
  EXPECT_EQ(e.mem_n.reg(Area::R, 4), 1u);    // a constant beyond int16: the handler
  EXPECT_EQ(e.mem_n.reg(Area::R, 5), 100u);  // .P: the word form on EN's rising edge
  EXPECT_TRUE(e.scan());
  EXPECT_EQ(e.mem_n.reg(Area::R, 1), 200u);
  EXPECT_EQ(e.mem_n.reg(Area::R, 5), 100u);
  EXPECT_TRUE(e.mem_n.bit(Area::Y, 0));
}

TEST(NativeFunForms, AThrowingHandlerFaultsBothEnginesAlike) {
  // The handler throws in the middle of a machine-code run: the networks before it have
  // run, those after it have not, on both engines; the program can run again.
  FormEngines e("ORG M1925\nOUT Y0\nORG X1\nTHROW D=R0\nOUT Y1\nORG M1925\nOUT Y2\nMOV S=7 D=R1\nEND\n");
  ASSERT_TRUE(e.native.native_active()) << e.native.engine_status();
  EXPECT_TRUE(e.scan());  // EN off: the handler does not run
  EXPECT_TRUE(e.mem_n.bit(Area::Y, 2));
  for (Memory* m : {&e.mem_i, &e.mem_n}) {
    m->set_bit(Area::Y, 2, false);
    m->set_reg(Area::R, 1, 0);
  }
  e.set_x(1, true);
  EXPECT_FALSE(e.scan());
  EXPECT_EQ(e.native.fault(), "forms.il:4: FUN 252 THROW failed: table full");
  EXPECT_TRUE(e.mem_n.bit(Area::Y, 0));
  EXPECT_FALSE(e.mem_n.bit(Area::Y, 1));
  EXPECT_FALSE(e.mem_n.bit(Area::Y, 2));
  EXPECT_EQ(e.mem_n.reg(Area::R, 1), 0u);
  for (Memory* m : {&e.mem_i, &e.mem_n}) m->set_reg(Area::R, 0, 3);
  EXPECT_FALSE(e.scan());
  EXPECT_EQ(e.native.fault(), "forms.il:4: FUN 252 THROW failed: an exception that is not a std::exception");
  e.set_x(1, false);
  EXPECT_TRUE(e.scan());
  EXPECT_EQ(e.mem_n.reg(Area::R, 1), 7u);
}

TEST(NativeFunForms, AThrowingHandlerStopsThePlcWithItsFault) {
  for (const EngineChoice engine : {EngineChoice::Interpreter, EngineChoice::Native, EngineChoice::Lockstep}) {
    Plc plc(probe_table());
    plc.locked([&](ScanEngine& e, Memory&) {
      e.set_engine(engine);
      return 0;
    });
    plc.load_program_text("ORG M1925\nTHROW D=R0\nEND\n", "boom.il");
    ASSERT_TRUE(plc.set_mode(RunMode::Run));
    plc.scan(1000);
    EXPECT_EQ(plc.mode(), RunMode::Stop) << engine_choice_name(engine);
    const std::string fault = plc.locked([](ScanEngine& e, Memory&) { return e.fault(); });
    EXPECT_EQ(fault, "boom.il:2: FUN 252 THROW failed: table full") << engine_choice_name(engine);
  }
}
