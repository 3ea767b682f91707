// plc_node as a scenario target: scans by clock messages, reads from the topics a robot
// stack subscribes to, drives through ~inputs_stamped/<name>, ~write, ~force, ~release and
// ~simulate.
//
// Synchronisation: plc_node publishes each topic on its own connection, so nothing orders
// them. After the clock message of the scan at t, plc_node publishes on
// ~virtual_time/scanned how many messages it has put on each topic since ~reset; the scan
// is complete here once that message says it scanned t and this node has received as many
// messages, stamped at or after the case's time 0, on every topic it reads. A stamped input
// is acknowledged the same way (ScanProgress.inputs) before the clock that scans it goes out.
#include "plc_cell/ros/scenario_ros_target.h"

#include <cmath>
#include <cstring>
#include <sstream>

#include "plc_cell/ForceDiscrete.h"
#include "plc_cell/ReleaseDiscrete.h"
#include "plc_cell/SimulateInputs.h"
#include "plc_cell/WriteMemory.h"
#include "plc_cell/core/address.h"
#include "plc_cell/core/area.h"
#include "plc_cell/core/error.h"
#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace scenario {

namespace {

// The position of a in a group's RegisterBlock values.
bool element_of(const RegisterGroup& g, const Address& a, size_t* idx) {
  size_t i = 0;
  for (const auto& sp : g.spans) {
    Address e = sp.start;
    const uint32_t stride = element_stride(e);
    for (uint32_t k = 0; k < sp.count; ++k, e.index += stride, ++i)
      if (e == a) {
        *idx = i;
        return true;
      }
  }
  return false;
}

}  // namespace

// ---- RosTarget ----

RosTarget::RosTarget(NodeLink& link, bool begin_case) : link_(link) {
  if (begin_case) link_.begin_case();
}

bool RosTarget::has_topic(const std::string& private_name) const {
  const std::string t = link_.node_ + "/" + private_name;
  return std::find(link_.topics_.begin(), link_.topics_.end(), t) != link_.topics_.end();
}

std::string RosTarget::topic_of(const Address& a) const {
  if ((a.area == Area::X || a.area == Area::Y) && a.width == Width::Bit && a.index < 256) return link_.node_ + "/io";
  for (const auto& s : link_.config_.signals)
    if (s.second == a && has_topic("signals_stamped/" + s.first)) return link_.node_ + "/signals_stamped/" + s.first;
  size_t idx;
  for (const auto& g : link_.config_.registers)
    if (element_of(g, a, &idx) && has_topic("registers/" + g.name)) return link_.node_ + "/registers/" + g.name;
  return "";
}

std::string RosTarget::check(const Probe& p, bool writing) {
  if (p.kind != Probe::Kind::Address) {
    const TopicProbes* side = link_.probes_of(p);
    if (!side) return p.text + ": plc_node has no topic for '" + p.family + ".'; run this case with `plc_cell test`";
    return side->check(p, writing, [this](const std::string& name) { return has_topic(name); });
  }
  Address a;
  try {
    a = link_.config_.resolve(p.name);
    check_format(a, p.format, p.text);
  } catch (const std::exception& e) {
    return e.what();
  }
  if (writing) return "";  // ~write, ~force take any address; set() on an X needs its name
  if (topic_of(a).empty() && !link_.read_fallback_)
    return p.name + " is on no topic of plc_node: add it to a group of the cell YAML's registers: (or, for a bit, "
                    "name it in signals:)";
  return "";
}

Reading RosTarget::read(const Probe& p) {
  if (p.kind != Probe::Kind::Address) {
    std::lock_guard<std::mutex> lk(link_.mu_);
    if (const TopicProbes* side = link_.probes_of(p)) return side->read(link_.node_, p);
    Reading r;
    r.valid = false;
    r.text = "unreadable";
    return r;
  }
  const Address a = link_.config_.resolve(p.name);
  const std::string topic = topic_of(a);
  if (topic.empty()) return address_reading(a, link_.read_memory(p.name), p.format);
  std::lock_guard<std::mutex> lk(link_.mu_);
  const NodeLink::Latest& l = *link_.latest_;
  uint32_t raw = 0;
  if (topic == link_.node_ + "/io") {
    if (l.have_io) {
      const auto& v = a.area == Area::X ? l.io.x : l.io.y;
      raw = a.index < v.size() && v[a.index];
    }
  } else if (l.signals.count(topic)) {
    raw = l.signals.at(topic);
  } else if (l.registers.count(topic)) {
    const std::string group = topic.substr(topic.rfind('/') + 1);
    size_t idx = 0;
    for (const auto& g : link_.config_.registers)
      if (g.name == group && element_of(g, a, &idx)) break;
    const auto& vals = l.registers.at(topic).values;
    if (idx < vals.size()) raw = uint32_t(vals[idx]);
  }
  return address_reading(a, raw, p.format);
}

void RosTarget::set(const Probe& p, const Value& v) {
  if (p.kind != Probe::Kind::Address) {
    TopicProbes* side = link_.probes_of(p);
    if (!side) throw Error(check(p, true));
    side->set(link_, p, v);
    return;
  }
  const Address a = link_.config_.resolve(p.name);
  if (a.area != Area::X || a.width != Width::Bit) {
    write(p, v);  // a held value of an internal point is a write
    return;
  }
  const auto it = link_.input_pubs_.find(a.index);
  if (it == link_.input_pubs_.end())
    throw Error(p.text + " has no input topic on plc_node: name it in the cell YAML's signals: (plc_node subscribes "
                         "~inputs_stamped/<name> for each named input)");
  Signal m;
  m.header.stamp = link_.next_input_stamp();
  m.data = v.number != 0;
  it->second.publish(m);
}

void RosTarget::write(const Probe& p, const Value& v) {
  if (p.kind != Probe::Kind::Address) throw Error(check(p, true));
  WriteMemory srv;
  srv.request.address = p.name;
  if (p.format == ValueFormat::F32) {
    const float f = float(v.number);
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    srv.request.values.push_back(bits);
  } else {
    srv.request.values.push_back(std::llround(v.number));
  }
  if (!ros::service::call(link_.node_ + "/write", srv)) throw Error("plc_node " + link_.node_ + ": ~write failed");
  if (!srv.response.success) throw Error(srv.response.message);
}

void RosTarget::force(const Probe& p, bool on) {
  ForceDiscrete srv;
  srv.request.address = p.name;
  srv.request.value = on;
  if (!ros::service::call(link_.node_ + "/force", srv)) throw Error("plc_node " + link_.node_ + ": ~force failed");
  if (!srv.response.success) throw Error(srv.response.message);
}

void RosTarget::release(const Probe* p) {
  ReleaseDiscrete srv;
  srv.request.address = p ? p->name : "";
  if (!ros::service::call(link_.node_ + "/release", srv)) throw Error("plc_node " + link_.node_ + ": ~release failed");
  if (!srv.response.success) throw Error(srv.response.message);
}

void RosTarget::simulate(const Probe* p) {
  SimulateInputs srv;
  if (p) srv.request.inputs.push_back(p->name);
  if (!ros::service::call(link_.node_ + "/simulate", srv)) throw Error("plc_node " + link_.node_ + ": ~simulate failed");
  if (!srv.response.success) throw Error(srv.response.message);
}

std::string RosTarget::fault() {
  std::lock_guard<std::mutex> lk(link_.mu_);
  return link_.have_progress_ ? link_.progress_.fault : "";
}

}  // namespace scenario
}  // namespace plc_cell
