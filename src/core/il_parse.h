#pragma once
// Internal: the IL parser's state, shared by the files that parse one concept each:
// il_parser.cpp (lines, statements, END, the whole program), il_operands.cpp (an
// operand's value or address), il_networks.cpp (contacts, outputs, TMR/CTR),
// il_flow.cpp (labels, jumps, routines, FOR/NEXT) and il_fun_line.cpp (FUN lines).
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "plc_cell/core/error.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/core/program.h"

namespace plc_cell {
namespace il {

using Token = IlToken;

std::string upper(std::string s);

struct FlowFun {
  uint16_t number;
  const char* name;
};
constexpr FlowFun kFlowFuns[] = {{65, "LBL"}, {66, "JMP"}, {67, "CALL"}, {68, "RTS"},
                                 {69, "RTI"}, {70, "FOR"}, {71, "NEXT"}};

class Parser {
 public:
  Parser(const std::string& file, const FunctionTable& fns) : fns_(fns) { prog_.file = file; }

  Program run(std::string_view text);

 private:
  void error(int column, const std::string& msg);
  Instruction& emit(Op op, const Token& at);
  void new_edge_slot();
  void statement(const std::vector<Token>& toks);
  void end(const std::vector<Token>& toks);
  void finish();

  // il_operands.cpp
  bool bit_address(const Token& t, Address* a);
  bool value_operand(const Token& t, bool is32, OperandRole role, uint8_t span, Operand* o);
  bool constant_operand(const Token& t, bool is32, OperandRole role, int64_t k, Operand* o);
  bool misspelt_constant(const Token& t, OperandRole role);
  bool register_operand(const Token& t, const Address& a, bool is32, uint8_t span, Operand* o);

  // il_networks.cpp
  bool need_network(const Token& t);
  // Output instructions consume the network's open LD blocks down to inputs-1.
  bool output_ok(const Token& t, int inputs);
  void contact(const std::string& m, const std::vector<Token>& toks);
  void out(const std::vector<Token>& toks);
  void set_rst(const std::string& m, const std::vector<Token>& toks);
  void timer_counter(const std::string& m, const std::vector<Token>& toks);

  // il_flow.cpp
  void check_open_fors(const Token& at);
  void flow(const std::string& m, const std::vector<Token>& toks, size_t first);
  void label(const Token& head, const Token& t);
  void jump(const std::string& m, const Token& head, const Token& t);
  void check_jumps();  // at the end: every JMP/CALL target, by region

  // il_fun_line.cpp
  void fun_numbered(const std::vector<Token>& toks);
  void fun(const FunctionSpec* spec, const std::string& mods, const Token& at, const std::vector<Token>& toks,
           size_t first);
  // The operands of a FUN line, by position or NAME=value, into ops; false on an error.
  bool fun_operands(const FunctionSpec* spec, const std::string& name, bool is32, const std::vector<Token>& toks,
                    size_t first, const Token& at, std::vector<Operand>* ops);

  struct Ref {
    size_t index;
    int column;
    bool in_sub;
  };
  const FunctionTable& fns_;
  Program prog_;
  std::vector<Diagnostic> errors_;
  std::vector<uint32_t> fors_;
  std::vector<Ref> refs_;
  std::map<std::string, bool> label_region_;
  int line_ = 0;
  int end_line_ = 0;
  int depth_ = 0;
  bool network_open_ = false;
  bool after_end_ = false;
  bool in_routine_ = false;
};

}  // namespace il
}  // namespace plc_cell
