#pragma once
// Reading YAML with errors that name file:line:column and the key path, e.g.
// "cell.yaml:3:5: error: key 'plc.scan_period': value 5 out of range [0.0001, 1]".
// Every config section (cell, counters, axes, modules, ...) reads through it.
#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/address.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {

class ErrorList;

class YamlReader {
 public:
  explicit YamlReader(std::string file) : file_(std::move(file)) {}

  // The document in text, or in the file itself; a syntax error names its line.
  YAML::Node load(const std::string& text) const;
  static YAML::Node load_file(const std::string& path);

  // Throws SourceError at n's position.
  [[noreturn]] void fail(const YAML::Node& n, const std::string& key, const std::string& msg) const;
  static int line(const YAML::Node& n) { return n.Mark().line >= 0 ? n.Mark().line + 1 : 0; }
  const std::string& file() const { return file_; }

  // f(); a plc_cell::Error it throws becomes this key's error at n (so the rules of a
  // value parser, such as a serial line's, report the line they were read from).
  template <typename F>
  auto checked(const YAML::Node& n, const std::string& key, F&& f) const -> decltype(f()) {
    try {
      return f();
    } catch (const SourceError&) {
      throw;
    } catch (const Error& e) {
      fail(n, key, e.what());
    }
  }

  // A mapping whose keys are all in allowed.
  void only(const YAML::Node& map, const std::string& key, const std::set<std::string>& allowed) const;
  // The same, reporting every unknown key into errors and going on (not a mapping: throws).
  void only(const YAML::Node& map, const std::string& key, const std::set<std::string>& allowed,
            ErrorList* errors) const;
  std::string str(const YAML::Node& n, const std::string& key) const;
  std::string choice(const YAML::Node& n, const std::string& key, const std::set<std::string>& allowed) const;
  double number(const YAML::Node& n, const std::string& key, double lo, double hi) const;
  int64_t integer(const YAML::Node& n, const std::string& key, int64_t lo, int64_t hi) const;
  uint64_t seconds_us(const YAML::Node& n, const std::string& key, double lo_s, double hi_s) const;
  uint64_t duration_us(const YAML::Node& n, const std::string& key) const;  // "2.5s", "100ms", ...
  bool boolean(const YAML::Node& n, const std::string& key) const;          // 0/1, true/false, on/off
  Address address(const YAML::Node& n, const std::string& key) const;
  AreaRange range(const YAML::Node& n, const std::string& key) const;       // M800-M1399 or R7
  Address data_register(const YAML::Node& n, const std::string& key) const;  // an R or D word
  // Where a line is, checked when the file is read rather than when it is opened:
  // HOST:PORT, and DEVICE[:BAUD[:FORMAT]] with format the default character framing.
  std::string host_port(const YAML::Node& n, const std::string& key) const;
  std::string serial_line(const YAML::Node& n, const std::string& key, const char* format) const;
  // A name that becomes part of a ROS topic: letters, digits and _, not first a digit.
  std::string topic_name(const YAML::Node& n, const std::string& key, const std::string& what) const;
  // A mapping of topic names to single discretes ({motor: Y0}), in file order.
  std::vector<std::pair<std::string, Address>> discretes(const YAML::Node& map, const std::string& key) const;

 private:
  std::string file_;
};

}  // namespace plc_cell
