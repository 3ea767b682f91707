#include "args.h"

#include <algorithm>

namespace plc_cell {
namespace cli {

Args::Args(const std::vector<std::string>& argv, const std::vector<std::string>& known,
           const std::vector<std::string>& flags) {
  auto is = [](const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
  };
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.rfind("--", 0) != 0) {
      positional_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    const auto eq = name.find('=');
    const bool inline_value = eq != std::string::npos;
    if (inline_value) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    if (is(flags, name)) {
      if (inline_value) throw UsageError("option --" + name + " takes no value");
      values_[name].push_back("1");
      continue;
    }
    if (!is(known, name)) throw UsageError("unknown option --" + name);
    if (!inline_value) {
      if (i + 1 >= argv.size()) throw UsageError("option --" + name + " needs a value");
      value = argv[++i];
    }
    values_[name].push_back(value);
  }
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second.back();
}

std::string Args::require(const std::string& name) const {
  if (!has(name)) throw UsageError("missing --" + name);
  return get(name);
}

long Args::get_int(const std::string& name, long fallback, long lo, long hi) const {
  if (!has(name)) return fallback;
  const std::string v = get(name);
  size_t used = 0;
  long n = 0;
  try {
    n = std::stol(v, &used, 0);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v.size())
    throw UsageError("--" + name + " takes a whole number, got '" + v + "'");
  if (n < lo || n > hi)
    throw UsageError("--" + name + " " + v + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
  return n;
}

std::vector<std::string> Args::all(const std::string& name) const {
  auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

std::vector<std::string> split_list(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == sep) {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

}  // namespace cli
}  // namespace plc_cell
