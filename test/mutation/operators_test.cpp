// The constant, preset and comparison operators on every form of an operand the IL parser
// accepts (docs/program-format.md): a FUN by number, by number and mnemonic or by mnemonic
// alone, operands named, positional or mixed, constants plain, K, H, 0x or 16#, words apart
// by spaces or commas, and lines of random such forms whose mutants must each parse and
// change exactly one constant by one.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "../core/run_tool.h"
#include "../core/tool_text.h"
#include "program_lines.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/mutation/mutant.h"

using namespace plc_cell;
using namespace plc_cell::mutation;
using plc_cell::testing::has;
using plc_cell::testing::program_lines;
using plc_cell::testing::run_tool;
using plc_cell::testing::slurp;
using plc_cell::testing::ToolResult;

namespace {

const FunctionTable& functions() {
  static const FunctionTable f = FunctionTable::with_core_functions();
  return f;
}

// The mutants of line 2 of "ORG M1925 / line / END" made by op, as their new text; each
// must parse.
std::vector<std::string> of(const std::string& line, const std::string& op, const std::string& after = "") {
  const std::string text = "ORG M1925\n" + line + "\n" + after + "END\n";
  const Program p = parse_program(text, "t.il", functions());
  std::vector<std::string> out;
  for (const Mutant& m : mutants(program_lines(text), p, functions())) {
    if (m.line != 2 || m.op != op) continue;
    out.push_back(m.after);
    EXPECT_NO_THROW(parse_program(mutation::apply(program_lines(text), m), "m.il", functions())) << m.after;
  }
  return out;
}

using Texts = std::vector<std::string>;

}  // namespace

TEST(ConstantOperator, EveryFormOfAFunLine) {
  EXPECT_EQ(of("FUN 11 ADD Sa=R0 Sb=10 D=R1", "constant"),
            (Texts{"FUN 11 ADD Sa=R0 Sb=11 D=R1", "FUN 11 ADD Sa=R0 Sb=9 D=R1"}));
  EXPECT_EQ(of("FUN 11 Sa=R0 Sb=10 D=R1", "constant"), (Texts{"FUN 11 Sa=R0 Sb=11 D=R1", "FUN 11 Sa=R0 Sb=9 D=R1"}));
  EXPECT_EQ(of("ADD Sa=R0 Sb=10 D=R1", "constant"), (Texts{"ADD Sa=R0 Sb=11 D=R1", "ADD Sa=R0 Sb=9 D=R1"}));
  EXPECT_EQ(of("ADD Sa=R0 Sb=K10 D=R1", "constant"), (Texts{"ADD Sa=R0 Sb=K11 D=R1", "ADD Sa=R0 Sb=K9 D=R1"}));
  EXPECT_EQ(of("FUN 11 ADD R0 10 R1", "constant"), (Texts{"FUN 11 ADD R0 11 R1", "FUN 11 ADD R0 9 R1"}));
  EXPECT_EQ(of("FUN 11 R0 K10 R1", "constant"), (Texts{"FUN 11 R0 K11 R1", "FUN 11 R0 K9 R1"}));
  EXPECT_EQ(of("ADD R0,10,R1", "constant"), (Texts{"ADD R0 11 R1", "ADD R0 9 R1"}));
  EXPECT_EQ(of("ADD D=R1 R0 10", "constant"), (Texts{"ADD D=R1 R0 11", "ADD D=R1 R0 9"}));
  EXPECT_EQ(of("add sa=r0 sb=h0a d=r1", "constant"), (Texts{"add sa=r0 sb=hB d=r1", "add sa=r0 sb=h9 d=r1"}));
  EXPECT_EQ(of("ADD.D Sa=DR0 Sb=0x1F D=DR2", "constant"),
            (Texts{"ADD.D Sa=DR0 Sb=0x20 D=DR2", "ADD.D Sa=DR0 Sb=0x1E D=DR2"}));
  EXPECT_EQ(of("FUN 11DP ADD Sa=R0 Sb=16#FF D=R2", "constant"),
            (Texts{"FUN 11DP ADD Sa=R0 Sb=16#100 D=R2", "FUN 11DP ADD Sa=R0 Sb=16#FE D=R2"}));
  EXPECT_EQ(of("ADD Sa=K-5 Sb=R0 D=R1", "constant"), (Texts{"ADD Sa=K-4 Sb=R0 D=R1", "ADD Sa=K-6 Sb=R0 D=R1"}));
  // A hexadecimal constant has no sign: H0 - 1 is written in decimal.
  EXPECT_EQ(of("ADD Sa=R0 Sb=H0 D=R1", "constant"), (Texts{"ADD Sa=R0 Sb=H1 D=R1", "ADD Sa=R0 Sb=-1 D=R1"}));
  // 65535 + 1 does not fit a 16-bit operand: no mutant the parser would refuse.
  EXPECT_EQ(of("ADD Sa=R0 Sb=65535 D=R1", "constant"), (Texts{"ADD Sa=R0 Sb=65534 D=R1"}));
  EXPECT_EQ(of("MOV S=5 D=R0 // five", "constant"), (Texts{"MOV S=6 D=R0", "MOV S=4 D=R0"}));
  EXPECT_EQ(of("FUN 8 5 R0", "constant"), (Texts{"FUN 8 6 R0", "FUN 8 4 R0"}));
  EXPECT_EQ(of("FOR 3", "constant", "ORG M1925\nOUT Y1\nNEXT\n"), (Texts{"FOR 4", "FOR 2"}));
  EXPECT_EQ(of("ADD Sa=R0 Sb=R5 D=R1", "constant"), Texts{});
}

TEST(ConstantOperator, PresetsInEveryForm) {
  EXPECT_EQ(of("TMR T50 K15", "preset"), (Texts{"TMR T50 K16", "TMR T50 K14", "TMR T50 K30", "TMR T50 K7"}));
  EXPECT_EQ(of("CTR C0 H10", "preset"), (Texts{"CTR C0 H11", "CTR C0 HF", "CTR C0 H20", "CTR C0 H8"}));
  EXPECT_EQ(of("CTR C200 40000", "preset"),
            (Texts{"CTR C200 40001", "CTR C200 39999", "CTR C200 80000", "CTR C200 20000"}));
}

TEST(ComparisonOperator, NamedAndPositionalFlags) {
  EXPECT_EQ(of("CMP Sa=R0 Sb=5 EQ=M51", "comparison"), (Texts{"CMP Sa=R0 Sb=5 GT=M51", "CMP Sa=R0 Sb=5 LT=M51"}));
  EXPECT_EQ(of("FUN 17 Sa=R0 Sb=5 EQ=M51 LT=M52", "comparison"),
            (Texts{"FUN 17 Sa=R0 Sb=5 GT=M51 LT=M52", "FUN 17 Sa=R0 Sb=5 EQ=M51 GT=M52"}));
  // A flag given by position moves by name, and every operand is then written by name so
  // that a positional one after it keeps its slot.
  EXPECT_EQ(of("FUN 17 CMP R0 5 M51", "comparison"),
            (Texts{"FUN 17 CMP Sa=R0 Sb=5 GT=M51", "FUN 17 CMP Sa=R0 Sb=5 LT=M51"}));
  EXPECT_EQ(of("CMP R0,5,M51,M52", "comparison"), (Texts{"CMP Sa=R0 Sb=5 LT=M51 GT=M52", "CMP Sa=R0 Sb=5 EQ=M51 LT=M52"}));
}

// Random FUN lines of the core's arithmetic and logic in every form: each constant operand
// gets its +1 and -1 mutants (where they fit), each parses, and each changes that constant
// by one and nothing else.
TEST(ConstantOperator, RandomFormsEachConstantByOne) {
  std::mt19937_64 rnd(20240611);
  auto pick = [&](size_t n) { return size_t(rnd() % n); };
  const std::vector<std::string> names = {"MOV", "MOVN", "ADD", "SUB", "MUL", "DIV", "CMP", "WAND", "WOR", "WXOR"};
  size_t checked = 0;
  for (int iteration = 0; iteration < 400; ++iteration) {
    const FunctionSpec* spec = functions().find(names[pick(names.size())]);
    ASSERT_NE(spec, nullptr);
    std::string line;
    switch (pick(3)) {
      case 0: line = "FUN " + std::to_string(spec->number); break;
      case 1: line = "FUN " + std::to_string(spec->number) + " " + spec->mnemonic; break;
      default: line = spec->mnemonic;
    }
    int flag = 50;
    for (const OperandSpec& o : spec->operands) {
      if (o.optional && pick(2)) break;  // the flags are last: an omitted one ends the line
      std::string value;
      if (o.role == OperandRole::Source && pick(3)) {
        const int64_t k = int64_t(pick(65536)) - 32768;
        const size_t form = k < 0 ? pick(2) : pick(5);
        const char* hex[] = {"H", "0x", "16#"};
        char buf[32];
        if (form >= 2) std::snprintf(buf, sizeof buf, "%s%llX", hex[form - 2], (unsigned long long)k);
        value = form == 0 ? std::to_string(k) : form == 1 ? "K" + std::to_string(k) : std::string(buf);
      } else {
        value = o.role == OperandRole::BitOut ? "M" + std::to_string(flag++) : "R" + std::to_string(pick(100) * 4);
      }
      line += pick(2) ? " " : ", ";
      line += pick(2) ? o.name + "=" + value : value;
    }
    if (pick(2))
      for (char& c : line) c = char(std::tolower(static_cast<unsigned char>(c)));
    const std::string text = "ORG X0\n" + line + "\nEND\n";
    const Program p = parse_program(text, "t.il", functions());
    const Instruction& in = p.code.at(1);
    std::set<std::pair<size_t, int64_t>> expected, made;
    for (size_t s = 0; s < in.operands.size(); ++s)
      if (in.operands[s].present && in.operands[s].kind == Operand::Kind::Const)
        for (int64_t v : {in.operands[s].k + 1, in.operands[s].k - 1})
          if (v >= -32768 && v <= 65535) expected.insert({s, v});
    for (const Mutant& m : mutants(program_lines(text), p, functions())) {
      if (m.op != "constant") continue;
      const Program q = parse_program(mutation::apply(program_lines(text), m), "m.il", functions());
      const Instruction& mi = q.code.at(1);
      ASSERT_EQ(mi.operands.size(), in.operands.size()) << line << " -> " << m.after;
      size_t changed = 0;
      for (size_t s = 0; s < in.operands.size(); ++s) {
        EXPECT_EQ(mi.operands[s].kind, in.operands[s].kind) << line << " -> " << m.after;
        EXPECT_EQ(mi.operands[s].addr, in.operands[s].addr) << line << " -> " << m.after;
        if (mi.operands[s].k == in.operands[s].k) continue;
        ++changed;
        made.insert({s, mi.operands[s].k});
      }
      EXPECT_EQ(changed, 1u) << line << " -> " << m.after;
    }
    EXPECT_EQ(made, expected) << line;
    checked += expected.size();
  }
  EXPECT_GT(checked, 300u);  // the generator made constants in many of its lines
}

// Through the tool: the constant mutants of each form are run (and killed by a case that
// checks each sum), and the lines every scan runs, ORG M1925, ANDLD and FOR among them,
// are executed by the case.
TEST(ConstantOperator, TheToolRunsThemAndEveryLineThatRanIsExecuted) {
  const std::string dir = ::testing::TempDir() + "/mutation_forms";
  std::system(("mkdir -p " + dir).c_str());
  std::ofstream(dir + "/cell.il") << "ORG M1925\n"
                                     "FUN 11 ADD Sa=R0 Sb=10 D=R1\n"
                                     "ADD Sa=R0 Sb=10 D=R2\n"
                                     "ADD Sa=R0 Sb=K10 D=R3\n"
                                     "FUN 11 ADD R0 10 R4\n"
                                     "ORG X0\n"
                                     "LD X1\n"
                                     "OR X2\n"
                                     "ANDLD\n"
                                     "OUT Y0\n"
                                     "FOR 2\n"
                                     "ORG M1925\n"
                                     "OUT Y5\n"
                                     "NEXT\n"
                                     "END\n";
  std::ofstream(dir + "/cell.yaml") << "cell: {name: t, program: cell.il}\nplc: {scan_period: 0.001}\n";
  std::ofstream(dir + "/s.scenario.yaml") << "cell: cell.yaml\ncases:\n"
                                             "  - name: sums\n    steps:\n"
                                             "      - at: 10ms\n        expect: R1 == 10 and R2 == 10 and R3 == 10 and R4 == 10\n";
  const std::string json = dir + "/m.json";
  const ToolResult r = run_tool("test " + dir + "/s.scenario.yaml --mutate --mutate-json " + json);
  EXPECT_EQ(r.status, 0) << r.out;
  const std::string j = slurp(json);
  auto mutant = [&](int line, const std::string& from, const std::string& to) {
    return "{\"line\": " + std::to_string(line) + ", \"network\": 1, \"network_line\": 1, \"operator\": \"constant\", "
           "\"from\": \"" + from + "\", \"to\": \"" + to + "\", \"status\": \"killed\", \"survival\": null, "
           "\"killed_by\": \"sums\"";
  };
  EXPECT_TRUE(has(j, mutant(2, "FUN 11 ADD Sa=R0 Sb=10 D=R1", "FUN 11 ADD Sa=R0 Sb=11 D=R1"))) << j;
  EXPECT_TRUE(has(j, mutant(3, "ADD Sa=R0 Sb=10 D=R2", "ADD Sa=R0 Sb=9 D=R2"))) << j;
  EXPECT_TRUE(has(j, mutant(4, "ADD Sa=R0 Sb=K10 D=R3", "ADD Sa=R0 Sb=K11 D=R3"))) << j;
  EXPECT_TRUE(has(j, mutant(5, "FUN 11 ADD R0 10 R4", "FUN 11 ADD R0 9 R4"))) << j;
  // ORG M1925 (its contact records nothing: M1925 cannot change) runs in every scan of the
  // case.
  EXPECT_TRUE(has(j, "\"from\": \"ORG M1925\", \"to\": \"ORG NOT M1925\", \"status\": \"killed\", \"survival\": "
                              "null, \"killed_by\": \"sums\", \"told_apart\": null, \"searched\": null, "
                              "\"executed_by\": [\"sums\"]}")) << j;
  // So do ANDLD (no value of its own) and FOR (none either).
  for (const std::string from : {"\"from\": \"ANDLD\", \"to\": \"ORLD\"", "\"from\": \"FOR 2\", \"to\": \"FOR 3\""}) {
    const size_t at = j.find(from);
    ASSERT_NE(at, std::string::npos) << from << "\n" << j;
    EXPECT_TRUE(has(j.substr(at, j.find('}', at) - at), "\"executed_by\": [\"sums\"]")) << from << "\n" << j;
  }
}
