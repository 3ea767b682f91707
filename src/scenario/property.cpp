#include "plc_cell/scenario/property.h"

#include <algorithm>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {

namespace {

// "A -> B": the text on each side of the one arrow, as a separate word.
bool split_arrow(const std::string& text, std::string* lhs, std::string* rhs) {
  const auto at = text.find("->");
  if (at == std::string::npos) return false;
  if (text.find("->", at + 2) != std::string::npos) throw Error("'" + text + "': one '->' per property");
  *lhs = text.substr(0, at);
  *rhs = text.substr(at + 2);
  return true;
}

}  // namespace

Property parse_property(bool never, const std::string& text, Naming naming) {
  Property p;
  p.never = never;
  p.text = std::string(never ? "never: " : "always: ") + text;
  std::string lhs, rhs;
  if (split_arrow(text, &lhs, &rhs)) {
    if (never) throw Error("'" + text + "': '->' goes with always (never: A -> B is always: A -> not B)");
    if (lhs.find_first_not_of(" \t") == std::string::npos) throw Error("'" + text + "': nothing before '->'");
    if (rhs.find_first_not_of(" \t") == std::string::npos) throw Error("'" + text + "': nothing after '->'");
    p.when = parse_condition(lhs, naming);
    p.cond = parse_condition(rhs, naming);
    return p;
  }
  p.cond = parse_condition(text, naming);
  return p;
}

bool Property::violated(const std::function<bool(const Condition&)>& holds) const {
  if (never) return holds(cond);
  return (when.empty() || holds(when)) && !holds(cond);
}

bool PropertyWatch::failed(bool violated_now, uint64_t now_us, uint64_t min_grace_us) {
  if (!violated_now) {
    violated_ = false;
    return false;
  }
  if (!violated_) {
    violated_ = true;
    since_us_ = now_us;
  }
  const uint64_t grace = std::max(p_->within_us, min_grace_us);
  return grace == 0 || now_us - since_us_ > grace;
}

}  // namespace scenario
}  // namespace plc_cell
