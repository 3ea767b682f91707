#include "plc_cell/ros/line_wire_topics.h"

namespace plc_cell {

std::string LineWireTopics::topic(const std::string& line_name, size_t wire) {
  return line_name + "/wires/" + std::to_string(wire);
}

LineWireTopics::LineWireTopics(ros::NodeHandle& nh, line::Line& line)
    : line_(line), nh_(nh), pubs_(line.wires().size()), subs_(line.wires().size()), sent_(line.wires().size(), 0),
      refused_(line.wires().size(), 0) {
  for (size_t w = 0; w < line.wires().size(); ++w) {
    const line::Wire& wire = line.wires()[w];
    if (line.cell(wire.from_cell) && !line.cell(wire.to_cell))
      pubs_[w] = nh_.advertise<WireSample>(topic(line.name(), w), 100, /*latch=*/true);
  }
  line.on_remote_sample([this](size_t w, uint64_t t_us, uint32_t value) { sampled(w, t_us, value); });
}

std::string LineWireTopics::text(size_t wire) const {
  const line::WireEntry& e = line_.wires()[wire].entry;
  return e.from + " -> " + e.to;
}

// ROS 1 queues a message for each subscriber's connection: the scan does not wait for one.
void LineWireTopics::sampled(size_t wire, uint64_t t_us, uint32_t value) {
  WireSample m;
  m.wire = text(wire);
  m.source_us = t_us;
  m.value = value;
  std::lock_guard<std::mutex> lk(mu_);
  sent_[wire] = 1;
  pubs_[wire].publish(m);
}

void LineWireTopics::start() {
  for (size_t w = 0; w < line_.wires().size(); ++w) {
    const line::Wire& wire = line_.wires()[w];
    if (pubs_[w]) {
      // The source's value after RUN, for a sink that did not see it change: unless a scan
      // already published a later one, which the latch must keep.
      WireSample m;
      m.wire = text(w);
      m.value = wire.initial;
      std::lock_guard<std::mutex> lk(mu_);
      if (!sent_[w]) pubs_[w].publish(m);
    } else if (line_.cell(wire.to_cell) && !line_.cell(wire.from_cell)) {
      subs_[w] = nh_.subscribe<WireSample>(topic(line_.name(), w), 100,
                                           [this, w](const WireSample::ConstPtr& m) { arrived(w, *m); });
    }
  }
}

// Another process that numbers the wires otherwise runs another line file: its values would
// drive the wrong inputs, so none is taken.
void LineWireTopics::arrived(size_t wire, const WireSample& m) {
  if (m.wire != text(wire)) {
    std::lock_guard<std::mutex> lk(mu_);
    if (!refused_[wire])
      ROS_ERROR("line %s: %s carries '%s', but wire %zu of %s is '%s': the processes run different line files; "
                "its values are not taken",
                line_.name().c_str(), nh_.resolveName(topic(line_.name(), wire)).c_str(), m.wire.c_str(), wire,
                line_.file().c_str(), text(wire).c_str());
    refused_[wire] = 1;
    return;
  }
  line_.receive(wire, m.value);
}

void LineWireTopics::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  std::vector<std::string> errors, warnings;
  size_t leaving = 0, arriving = 0;
  for (size_t w = 0; w < pubs_.size(); ++w) {
    const std::string name = "wire " + std::to_string(w) + " (" + text(w) + ")";
    if (pubs_[w]) {
      ++leaving;
      if (pubs_[w].getNumSubscribers() == 0)
        warnings.push_back(name + ": no process takes " + pubs_[w].getTopic());
    } else if (subs_[w]) {
      ++arriving;
      bool refused;
      {
        std::lock_guard<std::mutex> lk(mu_);
        refused = refused_[w];
      }
      if (refused)
        errors.push_back(name + ": " + subs_[w].getTopic() + " carries another wire (another line file)");
      else if (subs_[w].getNumPublishers() == 0)
        errors.push_back(name + ": no process publishes " + subs_[w].getTopic() + ": " + line_.wires()[w].entry.to +
                         " holds the last value it got");
    }
    stat.add(name, pubs_[w] ? "leaves on " + pubs_[w].getTopic()
                   : subs_[w] ? "arrives on " + subs_[w].getTopic() : std::string("in this process or none"));
  }
  const std::string counts = std::to_string(leaving) + " leaving, " + std::to_string(arriving) + " arriving";
  auto joined = [](const std::vector<std::string>& v) {
    std::string out;
    for (const auto& s : v) out += (out.empty() ? "" : "; ") + s;
    return out;
  };
  if (!errors.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, joined(errors));
  else if (!warnings.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, joined(warnings));
  else stat.summary(diagnostic_msgs::DiagnosticStatus::OK, counts);
}

}  // namespace plc_cell
