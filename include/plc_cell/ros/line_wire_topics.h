#pragma once
// The wires of a line split over several processes (docs/lines.md, "On ROS"): a wire whose
// source cell is here and sink cell elsewhere publishes each change of its source on
// /<line>/wires/<index> (plc_cell/WireSample, latched: a process that starts later gets the
// present value), and a wire whose sink is here takes it from there into Line::receive. A
// wire with both ends here is carried by the line itself; one with neither, by nobody here.
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "plc_cell/WireSample.h"
#include "plc_cell/line/line.h"

namespace plc_cell {

class LineWireTopics {
 public:
  // nh: the namespace the line's name goes under. Advertises the wires leaving this
  // process and sets the line's on_remote_sample: before the line runs.
  LineWireTopics(ros::NodeHandle& nh, line::Line& line);
  // Once the line runs: the first value of each wire leaving (unless a scan sent one), and
  // the subscriptions of the wires arriving, which deliver from then on.
  void start();
  // "/example_line/wires/3"
  static std::string topic(const std::string& line_name, size_t wire);
  // On /diagnostics: an ERROR for each wire arriving that no process publishes (its source's
  // process is not running: the sink holds the last value it got) or that carries another
  // wire; a WARN for each leaving that no process takes. OK with how many cross.
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);

 private:
  void sampled(size_t wire, uint64_t t_us, uint32_t value);  // a source's scan thread
  void arrived(size_t wire, const WireSample& m);             // the subscription's thread
  std::string text(size_t wire) const;

  line::Line& line_;
  ros::NodeHandle nh_;
  std::vector<ros::Publisher> pubs_;  // per wire: valid when its source is here, its sink not
  std::vector<ros::Subscriber> subs_;  // per wire: valid when its sink is here, its source not
  std::mutex mu_;            // one publish per wire at a time, so the latched value is the last
  std::vector<char> sent_;   // per wire: a scan's sample went out
  std::vector<char> refused_;  // per wire: a sample of another wire came, said once
};

}  // namespace plc_cell
