#pragma once
// The three renderings of coverage reports (docs/coverage.md): a text summary with the
// findings as file:line, a JSON document, and a self-contained HTML page. All are
// deterministic: the same reports give the same bytes.
#include <ostream>
#include <string>
#include <vector>

#include "plc_cell/coverage/report.h"

namespace plc_cell {
namespace coverage {

void write_text(const std::vector<Report>& reports, std::ostream& out);
void write_json(const std::vector<Report>& reports, std::ostream& out);
// Writes dir/index.html, creating dir (and its parents); throws Error on failure. extra:
// sections (HTML) other reports add after the programs (the mutation run's).
void write_html(const std::vector<Report>& reports, const std::string& dir, const std::string& extra = "");

}  // namespace coverage
}  // namespace plc_cell
