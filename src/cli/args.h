#pragma once
// Minimal option parsing for the plc_cell tool: --name value, --name=value, repeats allowed.
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace plc_cell {
namespace cli {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Args {
 public:
  // known: option names that take a value; flags: options without one.
  Args(const std::vector<std::string>& argv, const std::vector<std::string>& known,
       const std::vector<std::string>& flags = {});

  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::string get(const std::string& name, const std::string& fallback = "") const;
  std::string require(const std::string& name) const;
  // An integer option in [lo, hi]; UsageError names the option otherwise.
  long get_int(const std::string& name, long fallback, long lo, long hi) const;
  std::vector<std::string> all(const std::string& name) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::map<std::string, std::vector<std::string>> values_;
  std::vector<std::string> positional_;
};

// Splits "a,b,c" (empty parts dropped).
std::vector<std::string> split_list(const std::string& s, char sep = ',');

}  // namespace cli
}  // namespace plc_cell
