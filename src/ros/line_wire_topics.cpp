#include "plc_cell/ros/line_wire_topics.h"

namespace plc_cell {

std::string LineWireTopics::topic(const std::string& line_name, size_t wire) {
  return line_name + "/wires/" + std::to_string(wire);
}

LineWireTopics::LineWireTopics(ros::NodeHandle& nh, line::Line& line)
    : line_(line), nh_(nh), pubs_(line.wires().size()), sent_(line.wires().size(), 0),
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
      subs_.push_back(nh_.subscribe<WireSample>(topic(line_.name(), w), 100,
                                                [this, w](const WireSample::ConstPtr& m) { arrived(w, *m); }));
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

}  // namespace plc_cell
