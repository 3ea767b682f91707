#pragma once
// The difference of two program texts, line by line: what the audit trail keeps of a change.
#include <string>
#include <vector>

namespace plc_cell {
namespace online {

// A unified diff (3 lines of context, "@@ -a,b +c,d @@" hunks) from old to next; "" when
// they are equal. Headers name the two sides.
std::string unified_diff(const std::string& old_text, const std::string& next_text, const std::string& old_name,
                         const std::string& next_name);

// The lines of next (1, 2, ...) that are not in old: added or changed, by the same line
// matching as unified_diff. What a gate's mutation testing mutates (docs/online-change.md).
std::vector<int> changed_lines(const std::string& old_text, const std::string& next_text);

// FNV-1a 64 of text, as 16 hex digits: a program's identity in the audit trail.
std::string text_hash(const std::string& text);

}  // namespace online
}  // namespace plc_cell
