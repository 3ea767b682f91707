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

// FNV-1a 64 of text, as 16 hex digits: a program's identity in the audit trail.
std::string text_hash(const std::string& text);

}  // namespace online
}  // namespace plc_cell
