// The program split into networks, each with its comment, IL lines and drawing.
#include "plc_cell/ladder/layout.h"

#include <set>
#include <sstream>

#include "elements.h"
#include "grid.h"
#include "rung.h"

namespace plc_cell {
namespace ladder {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The source by line (1-based): the text, and where its comment starts (npos: none),
// the same markers the parser stops at.
struct Source {
  std::vector<std::string> lines{""};
  std::vector<size_t> comment_at{std::string::npos};

  explicit Source(std::string_view text) {
    std::istringstream in{std::string(text)};
    std::string line;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      size_t at = std::string::npos;
      for (size_t i = 0; i < line.size() && at == std::string::npos; ++i)
        if (line[i] == ';' || (line[i] == '/' && i + 1 < line.size() && line[i + 1] == '/')) at = i;
      lines.push_back(line);
      comment_at.push_back(at);
    }
  }
  bool has(int n) const { return n > 0 && static_cast<size_t>(n) < lines.size(); }
  bool comment_only(int n) const {
    return has(n) && comment_at[n] != std::string::npos && trim(lines[n].substr(0, comment_at[n])).empty();
  }
  std::string comment(int n) const {
    if (!has(n) || comment_at[n] == std::string::npos) return "";
    size_t b = comment_at[n];
    b += lines[n][b] == ';' ? 1 : 2;
    while (b < lines[n].size() && lines[n][b] == ';') ++b;
    return trim(lines[n].substr(b));
  }
  // The comment lines right above line n (no blank line between), top to bottom.
  std::string above(int n) const {
    int top = n;
    while (comment_only(top - 1)) --top;
    std::string out;
    for (int k = top; k < n; ++k) out += (k > top ? "\n" : "") + comment(k);
    return out;
  }
};

bool starts_network(Op op) {
  return op == Op::Org || op == Op::OrgNot || op == Op::OrgUp || op == Op::OrgDown;
}

// [first, end) of each network: ORG up to the next ORG or flow instruction; each flow
// instruction alone.
std::vector<std::pair<uint32_t, uint32_t>> split(const Program& p) {
  std::vector<std::pair<uint32_t, uint32_t>> nets;
  const uint32_t n = static_cast<uint32_t>(p.code.size());
  for (uint32_t i = 0; i < n;) {
    uint32_t j = i + 1;
    if (!is_flow(p.code[i].op))
      while (j < n && !is_flow(p.code[j].op) && !starts_network(p.code[j].op)) ++j;
    nets.emplace_back(i, j);
    i = j;
  }
  return nets;
}

void fill_il(const Program& p, const Source& src, Network* net) {
  const int from = p.code[net->first].line, to = p.code[net->end - 1].line;
  for (int k = from; k <= to; ++k)
    if (src.has(k) && !trim(src.lines[k]).empty()) net->il.push_back({k, trim(src.lines[k])});
}

}  // namespace

Layout layout(const Program& program, std::string_view text, const Signals& signals,
              const FunctionTable* functions) {
  Layout out;
  out.file = program.file;
  out.signals = signals;
  const Source src(text);
  std::vector<std::string> line_comments(src.lines.size());
  for (size_t k = 1; k < src.lines.size(); ++k)
    if (!src.comment_only(static_cast<int>(k))) line_comments[k] = src.comment(static_cast<int>(k));
  const Names names(signals);
  const Drawer drawer(program, names, functions, line_comments);
  for (const auto& range : split(program)) {
    Network net;
    net.index = static_cast<int>(out.networks.size());
    net.first = range.first;
    net.end = range.second;
    net.line = program.code[range.first].line;
    net.comment = src.above(net.line);
    fill_il(program, src, &net);
    const Op op = program.code[range.first].op;
    if (is_flow(op)) {
      draw_flow(range.first, drawer, &net);
    } else if (!starts_network(op)) {
      net.drawable = false;
      net.reason = "line " + std::to_string(net.line) + ": the network does not start with ORG";
    } else {
      const Rung rung = build_rung(program, range.first, range.second);
      net.reason = rung.reason;
      net.drawable = rung.reason.empty();
      if (net.drawable) draw_rung(rung, drawer, &net);
    }
    out.networks.push_back(std::move(net));
  }
  return out;
}

std::vector<Address> addresses(const Network& network) {
  std::vector<Address> out;
  std::set<uint64_t> seen;
  auto add = [&](const std::string& text) {
    if (text.empty()) return;
    const Address a = parse_address(text);
    if (seen.insert(address_key(a)).second) out.push_back(a);
  };
  for (const Element& e : network.elements) {
    if (e.values.empty()) add(e.address);
    for (const std::string& v : e.values) add(v);
    add(e.preset_address);
    for (const FunOperand& o : e.operands) add(o.address);
  }
  return out;
}

}  // namespace ladder
}  // namespace plc_cell
