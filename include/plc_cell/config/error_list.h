#pragma once
// The errors of several independent parts of one input, found in one run: each part is
// read even when an earlier one failed, so a user fixes a whole cell file at once (the IL
// parser does the same for a program). A cell is built through it by SoftCell, and so by
// plc_cell check, sim and run and by plc_node alike.
#include <algorithm>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/error.h"

namespace plc_cell {

class ErrorList {
 public:
  // Runs part(). A SourceError's diagnostics are kept; another plc_cell::Error or a
  // yaml-cpp exception becomes one diagnostic in `file`, at the exception's own mark when
  // it has one, else at `at` (the section being read). Returns whether part() succeeded.
  template <typename F>
  bool collect(F&& part, const std::string& file, const YAML::Node& at = YAML::Node()) {
    try {
      part();
      return true;
    } catch (const SourceError& e) {
      add(e);
    } catch (const Error& e) {
      add(diagnostic(file, at, e.what()));
    } catch (const YAML::Exception& e) {
      Diagnostic d = diagnostic(file, at, e.msg);
      if (!e.mark.is_null()) d.where.line = e.mark.line + 1, d.where.column = e.mark.column + 1;
      add(d);
    }
    return false;
  }

  void add(const SourceError& e) {
    for (const auto& d : e.diagnostics()) add(d);
  }
  // The same error found twice (two subsystems reading one key) is listed once.
  void add(Diagnostic d) {
    for (const auto& o : list_)
      if (o.where.file == d.where.file && o.where.line == d.where.line && o.where.column == d.where.column &&
          o.message == d.message)
        return;
    list_.push_back(std::move(d));
  }
  bool empty() const { return list_.empty(); }
  size_t size() const { return list_.size(); }
  const std::vector<Diagnostic>& diagnostics() const { return list_; }
  // Throws one SourceError listing every error, file by file in the order the files were
  // read and by line within a file; nothing if there is none.
  void throw_if_any() const {
    if (list_.empty()) return;
    std::vector<std::string> files;
    auto rank = [&](const Diagnostic& d) {
      return size_t(std::find(files.begin(), files.end(), d.where.file) - files.begin());
    };
    for (const auto& d : list_)
      if (rank(d) == files.size()) files.push_back(d.where.file);
    std::vector<Diagnostic> sorted = list_;
    std::stable_sort(sorted.begin(), sorted.end(), [&](const Diagnostic& a, const Diagnostic& b) {
      return std::make_tuple(rank(a), a.where.line, a.where.column) < std::make_tuple(rank(b), b.where.line, b.where.column);
    });
    throw SourceError(sorted);
  }

  static Diagnostic diagnostic(const std::string& file, const YAML::Node& at, const std::string& message) {
    Diagnostic d;
    d.where.file = file;
    if (at.IsDefined() && !at.Mark().is_null()) {
      d.where.line = at.Mark().line + 1;
      d.where.column = at.Mark().column + 1;
    }
    d.message = message;
    return d;
  }

 private:
  std::vector<Diagnostic> list_;
};

}  // namespace plc_cell
