#include <ostream>

#include "plc_cell/coverage/outputs.h"

namespace plc_cell {
namespace coverage {

namespace {

std::string quoted(const std::string& s) {
  static const char* const hex = "0123456789abcdef";
  std::string q = "\"";
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"': q += "\\\""; break;
      case '\\': q += "\\\\"; break;
      case '\n': q += "\\n"; break;
      case '\r': q += "\\r"; break;
      case '\t': q += "\\t"; break;
      default:
        if (c < 0x20) {
          q += "\\u00";
          q += hex[c >> 4];
          q += hex[c & 15];
        } else {
          q += ch;  // UTF-8 passes through: JSON text is UTF-8
        }
    }
  }
  return q + "\"";
}

const char* boolean(bool b) { return b ? "true" : "false"; }

const char* kind_name(ItemKind k) {
  switch (k) {
    case ItemKind::Contact: return "contact";
    case ItemKind::Coil: return "coil";
    case ItemKind::Fun: return "fun";
  }
  return "";
}

std::string seen(const Item& it) {
  if (it.seen_off && it.seen_on) return "[\"off\", \"on\"]";
  if (it.seen_off) return "[\"off\"]";
  if (it.seen_on) return "[\"on\"]";
  return "[]";
}

void totals(const Totals& t, std::ostream& out) {
  out << "{\"networks\": " << t.networks << ", \"networks_evaluated\": " << t.networks_evaluated
      << ", \"networks_energised\": " << t.networks_energised << ", \"contacts\": " << t.contacts
      << ", \"contacts_changed\": " << t.contacts_changed << ", \"contacts_mcdc\": " << t.contacts_mcdc
      << ", \"coils\": " << t.coils
      << ", \"coils_switched\": " << t.coils_switched << ", \"funs\": " << t.funs
      << ", \"funs_enabled\": " << t.funs_enabled << "}";
}

void network(const Network& n, std::ostream& out) {
  out << "        {\"number\": " << n.number << ", \"line\": " << n.line << ", \"end_line\": " << n.end_line
      << ", \"routine\": " << quoted(n.routine) << ", \"evaluated\": " << boolean(n.evaluated)
      << ", \"energised\": " << boolean(n.energised) << ",\n         \"items\": [";
  for (size_t i = 0; i < n.items.size(); ++i) {
    const Item& it = n.items[i];
    out << (i ? ",\n" : "\n") << "           {\"kind\": \"" << kind_name(it.kind) << "\", \"line\": " << it.line
        << ", \"name\": " << quoted(it.name) << (it.signal.empty() ? "" : ", \"signal\": " + quoted(it.signal))
        << ", \"seen\": " << seen(it)
        << ", \"exercised\": " << boolean(it.exercised())
        << (it.kind == ItemKind::Contact ? std::string(", \"mcdc\": ") + boolean(it.mcdc) : "") << "}";
  }
  out << (n.items.empty() ? "]}" : "\n         ]}");
}

}  // namespace

void write_json(const std::vector<Report>& reports, std::ostream& out) {
  out << "{\n  \"format\": \"plc_cell coverage\",\n  \"version\": 1,\n  \"programs\": [";
  for (size_t p = 0; p < reports.size(); ++p) {
    const Report& r = reports[p];
    out << (p ? ",\n" : "\n") << "    {\n      \"file\": " << quoted(r.file) << ",\n      \"runs\": " << r.runs
        << ",\n      \"totals\": ";
    totals(r.totals, out);
    out << ",\n      \"networks\": [";
    for (size_t i = 0; i < r.networks.size(); ++i) {
      out << (i ? ",\n" : "\n");
      network(r.networks[i], out);
    }
    out << (r.networks.empty() ? "],\n" : "\n      ],\n") << "      \"findings\": [";
    for (size_t i = 0; i < r.findings.size(); ++i)
      out << (i ? ",\n" : "\n") << "        {\"line\": " << r.findings[i].line
          << ", \"message\": " << quoted(r.findings[i].message) << "}";
    out << (r.findings.empty() ? "]\n" : "\n      ]\n") << "    }";
  }
  out << (reports.empty() ? "]\n}\n" : "\n  ]\n}\n");
}

}  // namespace coverage
}  // namespace plc_cell
