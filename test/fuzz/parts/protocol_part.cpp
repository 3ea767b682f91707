#include <sstream>

#include "../cell_part.h"

namespace plc_cell_fuzz {
namespace {

// FUN150 (Modbus master) and FUN151 (FATEK CLINK) on ports nobody answers
// (docs/fatek.md, docs/modbus.md): the requests time out and the functions report it.
void protocol(CellDraft& d) {
  Fdp& f = d.f;
  if (!chance(f, 4)) return;
  static const char* const fatek_ports[] = {"tcp:127.0.0.1:9", "tcp:127.0.0.1:1"};
  d.section("fatek") << "  timeout_ms: " << f.ConsumeIntegralInRange<int>(10, 100) << "\n  ports:\n    1: "
                     << pick(f, fatek_ports) << "\n";
  d.section("modbus") << "  ports:\n    2: {tcp: 127.0.0.1:9}\n";
  for (int i = 0; i < 16; ++i) d.init << "MOV S=" << f.ConsumeIntegralInRange<int>(0, 0xFFFF) << " D=R" << 1500 + i << "\n";
  d.body << "ORG M1925\nLD M706\nLD M707\nFUN 151 Pt=1 MD=" << f.ConsumeIntegralInRange<int>(0, 2)
         << " SR=R1500 WR=R1540 ACT=M120 ERR=M121 DN=M122\n"
         << "ORG M1925\nLD M708\nLD M709\nFUN 150 Pt=2 SR=R1500 WR=R1560 ACT=M123 ERR=M124 DN=M125\n";
}

const RegisterCellPart registered({"protocol functions", 40, protocol});

}  // namespace
}  // namespace plc_cell_fuzz
