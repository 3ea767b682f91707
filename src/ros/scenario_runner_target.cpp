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
#include <cstdio>
#include <cstring>
#include <sstream>

#include <sensor_msgs/Temperature.h>

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

RosTarget::RosTarget(NodeLink& link) : link_(link) { link_.begin_case(); }

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
  switch (p.kind) {
    case Probe::Kind::Address: {
      Address a;
      try {
        a = link_.config_.resolve(p.name);
      } catch (const std::exception& e) {
        return e.what();
      }
      try {
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
    case Probe::Kind::Counter:
      if (writing) return p.text + ": plc_node has no topic or service that sets a counter in a scenario";
      if (!has_topic("counters/" + p.name))
        return p.text + ": plc_node publishes no ~counters/" + p.name + " (no counter of that name in the cell)";
      return "";
    case Probe::Kind::AxisPosition:
    case Probe::Kind::AxisState:
    case Probe::Kind::AxisFrequency:
      if (writing) return p.text + ": an axis cannot be driven by a scenario step";
      if (!has_topic("motion/" + p.name + "/status"))
        return p.text + ": plc_node publishes no ~motion/" + p.name + "/status (no axis of that name in the cell)";
      return "";
    case Probe::Kind::Temperature:
      if (!has_topic("temperature/" + p.name))
        return p.text + ": plc_node publishes no ~temperature/" + p.name + " (no channel of that name in the cell)";
      return "";
    case Probe::Kind::PulseWidth:
    case Probe::Kind::PulsePeriod:
    case Probe::Kind::PulseFrequency:
      if (writing) return p.text + ": a pulse measurement is read, not driven";
      if (!has_topic("pulses/" + p.name))
        return p.text + ": plc_node publishes no ~pulses/" + p.name + " (the input is not measured in the cell)";
      return "";
    case Probe::Kind::Analog:
      return p.text + ": plc_node has no topic for analog input channels" +
             std::string(writing ? " and no way to set one" : "") + "; run this case with `plc_cell test`";
  }
  return p.text + ": unknown probe";
}

Reading RosTarget::read(const Probe& p) {
  if (p.kind == Probe::Kind::Address) {
    const Address a = link_.config_.resolve(p.name);
    if (topic_of(a).empty()) return address_reading(a, link_.read_memory(p.name), p.format);
  }
  std::lock_guard<std::mutex> lk(link_.mu_);
  const NodeLink::Latest& l = *link_.latest_;
  Reading r;
  switch (p.kind) {
    case Probe::Kind::Address: {
      const Address a = link_.config_.resolve(p.name);
      const std::string topic = topic_of(a);
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
    case Probe::Kind::Counter: {
      const auto it = l.counters.find(link_.node_ + "/counters/" + p.name);
      r.number = it == l.counters.end() ? 0 : double(it->second.count);
      r.text = probe_number_text(r.number);
      return r;
    }
    case Probe::Kind::AxisPosition:
    case Probe::Kind::AxisState:
    case Probe::Kind::AxisFrequency: {
      const auto it = l.axes.find(link_.node_ + "/motion/" + p.name + "/status");
      AxisStatus s;
      if (it != l.axes.end()) s = it->second;
      // As the cell in process reads it: pulses, Hz signed by the direction, and the state
      // an error code, else pulses going out, else idle.
      if (p.kind == Probe::Kind::AxisState) {
        r.word = s.error ? "error" : s.frequency != 0 ? "moving" : "idle";
        r.number = s.error;
        r.text = s.error ? "error " + std::to_string(s.error) : r.word;
        return r;
      }
      r.number = p.kind == Probe::Kind::AxisPosition ? double(s.pulses) : s.frequency;
      r.text = probe_number_text(r.number);
      return r;
    }
    case Probe::Kind::Temperature: {
      const auto it = l.temperatures.find(link_.node_ + "/temperature/" + p.name);
      const double c = it == l.temperatures.end() ? std::nan("") : it->second;
      r.valid = std::isfinite(c);  // NaN: a broken line
      r.number = r.valid ? c : 0;
      r.text = r.valid ? probe_number_text(std::round(c * 1000) / 1000) + " C" : "NaN (broken)";
      return r;
    }
    case Probe::Kind::PulseWidth:
    case Probe::Kind::PulsePeriod:
    case Probe::Kind::PulseFrequency: {
      const auto it = l.pulses.find(link_.node_ + "/pulses/" + p.name);
      PulseMeasurement m;
      if (it != l.pulses.end()) m = it->second;
      r.number = p.kind == Probe::Kind::PulseWidth ? m.width : p.kind == Probe::Kind::PulsePeriod ? m.period : m.frequency;
      r.text = probe_number_text(r.number);
      return r;
    }
    case Probe::Kind::Analog:
      break;
  }
  r.valid = false;
  r.text = "unreadable";
  return r;
}

void RosTarget::set(const Probe& p, const Value& v) {
  if (p.kind == Probe::Kind::Temperature) {
    const auto it = link_.temperature_pubs_.find(p.name);
    if (it == link_.temperature_pubs_.end()) throw Error(check(p, true));
    if (v.has_unit && v.quantity.unit != temp::Unit::Celsius)
      throw Error(p.text + ": " + v.text + ": plc_node's ~temperature_inputs/" + p.name +
                  " takes degrees C (a sensor's mV or ohm only with `plc_cell test`)");
    sensor_msgs::Temperature m;
    {
      std::lock_guard<std::mutex> lk(link_.mu_);
      const uint64_t next = link_.scanned_ ? link_.last_t_us_ + link_.period_us_ : 0;
      m.header.stamp.fromNSec((link_.t0_us_ + next) * 1000);
      ++link_.inputs_sent_;
    }
    m.temperature = v.has_unit ? v.quantity.value : v.number;
    it->second.publish(m);
    return;
  }
  if (p.kind != Probe::Kind::Address) throw Error(check(p, true));
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
  {
    std::lock_guard<std::mutex> lk(link_.mu_);
    const uint64_t next = link_.scanned_ ? link_.last_t_us_ + link_.period_us_ : 0;
    m.header.stamp.fromNSec((link_.t0_us_ + next) * 1000);
    ++link_.inputs_sent_;
  }
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
