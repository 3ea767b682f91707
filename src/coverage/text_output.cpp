#include <ostream>

#include "plc_cell/coverage/outputs.h"
#include "ratio_text.h"

namespace plc_cell {
namespace coverage {

void write_text(const std::vector<Report>& reports, std::ostream& out) {
  bool first = true;
  for (const Report& r : reports) {
    if (!first) out << '\n';
    first = false;
    const Totals& t = r.totals;
    out << "coverage of " << r.file << " (" << r.runs << (r.runs == 1 ? " run" : " runs") << ")\n"
        << "  networks evaluated " << ratio(t.networks_evaluated, t.networks) << ", energised "
        << ratio(t.networks_energised, t.networks) << '\n'
        << "  contacts changed " << ratio(t.contacts_changed, t.contacts) << ", coils switched "
        << ratio(t.coils_switched, t.coils) << ", FUNs enabled " << ratio(t.funs_enabled, t.funs) << '\n'
        << "  contacts with MC/DC (unique cause) " << ratio(t.contacts_mcdc, t.contacts) << '\n';
    if (r.findings.empty()) out << "  every network, contact, coil and FUN exercised\n";
    for (const Finding& f : r.findings) out << r.file << ':' << f.line << ' ' << f.message << '\n';
    // A contact that changed, but never alone changed its network's outcome.
    for (const Network& n : r.networks)
      for (const Item& it : n.items)
        if (it.kind == ItemKind::Contact && it.exercised() && !it.mcdc)
          out << r.file << ':' << it.line << " contact " << label(it) << " never decided network " << n.number
              << " (line " << n.line << ") alone (MC/DC)\n";
  }
}

}  // namespace coverage
}  // namespace plc_cell
