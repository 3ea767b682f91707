#include "plc_cell/ros/line_virtual_time.h"

#include <algorithm>

#include <rosgraph_msgs/Clock.h>

#include "plc_cell/ScanProgress.h"
#include "plc_cell/core/error.h"
#include "plc_cell/ros/frame_id.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {

// A cell's plc_node side in the line's virtual time: what a lone node's VirtualTimeDriver
// does for its cell, with the scans left to the line's clock.
class LineVirtualClock::CellDriver : public ScanDriver {
 public:
  CellDriver(LineVirtualClock& clock, size_t cell, Host& host, std::string line_name)
      : clock_(clock), cell_(cell), host_(host), line_name_(std::move(line_name)) {}
  Host& host() { return host_; }
  void start() override {}  // the line's clock scans
  void input(TimedInput in) override { clock_.input(cell_, std::move(in)); }
  ros::Time stamp(uint64_t cell_us) const override {
    ros::Time t;
    t.fromNSec((clock_.epoch_us_ + cell_us) * 1000);
    return t;
  }
  void post(std::function<void()> fn) override { fn(); }  // on the clock's thread, at the scan
  bool republishes() const override { return false; }
  std::string reset_refusal() const override {
    return "~reset: this cell is part of a line, whose wires hold the other cells' state: call " + line_name_ +
           "/reset for a fresh line (every cell at once)";
  }
  void reset(const std::function<void()>&) override {}

 private:
  LineVirtualClock& clock_;
  size_t cell_;
  Host& host_;
  std::string line_name_;
};

LineVirtualClock::LineVirtualClock(ros::NodeHandle& pnh, const std::string& line_name,
                                   diagnostic_updater::Updater& updater)
    : pnh_(pnh) {
  pnh.param<std::string>("clock_topic", clock_topic_, "/clock");
  clock_topic_ = pnh.resolveName(clock_topic_);
  double lag = 0.1;
  XmlRpc::XmlRpcValue v;
  if (pnh.getParam("virtual_time_lag", v)) {
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) lag = double(v);
    else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) lag = int(v);
    else lag = -1;  // not a number: refused below, not read as the default
  }
  if (!(lag >= 0 && lag <= 60)) throw Error("~virtual_time_lag: a number of seconds in [0, 60]");
  lag_us_ = uint64_t(lag * 1e6);
  updater.add("virtual time", [this, line_name](diagnostic_updater::DiagnosticStatusWrapper& stat) {
    std::lock_guard<std::mutex> lk(mu_);
    if (!line_) return;
    std::string late;
    uint64_t pending = 0;
    for (size_t i = 0; i < cells_.size(); ++i) {
      if (!cells_[i].driver) continue;
      pending += cells_[i].pending.size();
      stat.add("late inputs: " + line_->entry(i).name, cells_[i].late_inputs);
      if (cells_[i].late_inputs)
        late += (late.empty() ? "" : ", ") + line_->entry(i).name + " " + std::to_string(cells_[i].late_inputs);
    }
    if (!late.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "inputs arrived after their scan: " + late);
    else stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "deterministic: line " + line_name + " on " + clock_topic_);
    stat.add("next instant (us)", next_us_);
    stat.add("pending inputs", pending);
  });
}

LineVirtualClock::~LineVirtualClock() { stop(); }

void LineVirtualClock::stop() {
  clock_sub_.shutdown();
  std::lock_guard<std::mutex> lk(mu_);
  stopped_ = true;
}

std::unique_ptr<ScanDriver> LineVirtualClock::driver(size_t cell, ros::NodeHandle& cell_pnh, ScanDriver::Host& host,
                                                     uint64_t period_us) {
  std::lock_guard<std::mutex> lk(mu_);
  if (cells_.size() <= cell) cells_.resize(cell + 1);
  PerCell& c = cells_[cell];
  const std::string line_ns = ros::names::parentNamespace(ros::names::parentNamespace(cell_pnh.getNamespace()));
  auto d = std::make_unique<CellDriver>(*this, cell, host, line_ns);
  c.driver = d.get();
  c.period_us = period_us;
  c.frame_id = frame_id_param(cell_pnh);
  c.progress = cell_pnh.advertise<ScanProgress>("virtual_time/scanned", 100);
  return d;
}

void LineVirtualClock::start(line::Line& line) {
  {
    std::lock_guard<std::mutex> lk(mu_);
    line_ = &line;
    cells_.resize(line.size());
    for (size_t i = 0; i < cells_.size(); ++i)
      if (cells_[i].driver) publish_progress(i);  // a driver sees the node's topics before its first clock
  }
  clock_sub_ = pnh_.subscribe<rosgraph_msgs::Clock>(clock_topic_, 1000, [this](const rosgraph_msgs::Clock::ConstPtr& m) {
    on_clock(m->clock.toNSec() / 1000);
  });
}

void LineVirtualClock::reset(line::Line& fresh, const std::function<void()>& swap) {
  std::lock_guard<std::mutex> lk(mu_);
  swap();
  line_ = &fresh;
  ++resets_;
  started_ = false;
  after_reset_ = true;
  clear_run();
  for (size_t i = 0; i < cells_.size(); ++i)
    if (cells_[i].driver) publish_progress(i);
}

void LineVirtualClock::clear_run() {
  for (PerCell& c : cells_) {
    c.scans = c.last_scan_us = c.input_seq = c.inputs_received = c.late_inputs = 0;
    c.pending.clear();
  }
  epoch_us_ = next_us_ = 0;
}

void LineVirtualClock::input(size_t cell, TimedInput in) {
  std::lock_guard<std::mutex> lk(mu_);
  if (stopped_) return;
  PerCell& c = cells_[cell];
  if (in.resume) {  // a hand-back: at the cell's next scan, not a stamped input
    in.stamp_us = next_us_;
    in.seq = c.input_seq++;
    c.pending.push_back(in);
    return;
  }
  if (c.scans && in.stamp_us <= c.last_scan_us) ++c.late_inputs;  // its scan ran: applied at the next
  in.seq = c.input_seq++;
  c.pending.push_back(in);
  ++c.inputs_received;
  publish_progress(cell);  // a driver knows the input is in before it sends the clock
}

void LineVirtualClock::on_clock(uint64_t now_us) {
  std::lock_guard<std::mutex> lk(mu_);  // one clock message at a time, in order
  if (!line_ || stopped_) return;
  const uint64_t tick = line_->tick_us();
  if (!started_) {
    // As a lone node's: on start the first message's instant, after a reset the first
    // instant it runs, rounded up to the line's tick.
    uint64_t first = now_us;
    if (after_reset_) {
      if (now_us < lag_us_) return;
      first = now_us - lag_us_;
    }
    next_us_ = epoch_us_ = (first + tick - 1) / tick * tick;
    started_ = true;
  }
  if (now_us >= lag_us_ + next_us_) {
    const uint64_t until = now_us - lag_us_;
    for (PerCell& c : cells_)
      std::stable_sort(c.pending.begin(), c.pending.end(), [](const TimedInput& a, const TimedInput& b) {
        return a.stamp_us != b.stamp_us ? a.stamp_us < b.stamp_us : a.seq < b.seq;
      });
    for (; next_us_ <= until; next_us_ += tick) instant(next_us_);
  }
  for (size_t i = 0; i < cells_.size(); ++i)
    if (cells_[i].driver) publish_progress(i);  // after every message of these scans
}

// The inputs due at each cell that scans at t, then the line's own instant: the scans in
// file order and the wires' deliveries are the core's.
void LineVirtualClock::instant(uint64_t t_us) {
  const uint64_t lt = t_us - epoch_us_;
  for (size_t i = 0; i < cells_.size(); ++i) {
    PerCell& c = cells_[i];
    if (!c.driver || lt % c.period_us != 0) continue;
    size_t k = 0;
    line_->cell(i)->plc().locked([&](ScanEngine& e, Memory&) {
      for (; k < c.pending.size() && c.pending[k].stamp_us <= t_us; ++k) c.driver->host().apply(e, c.pending[k]);
      return 0;
    });
    c.pending.erase(c.pending.begin(), c.pending.begin() + long(k));
  }
  line_->scan_at(lt);  // after each cell's scan: scanned() below, through the line's after_scan
}

void LineVirtualClock::scanned(size_t cell, uint64_t lt_us) {
  PerCell& c = cells_[cell];
  c.driver->host().scanned();
  ++c.scans;
  c.last_scan_us = epoch_us_ + lt_us;
}

void LineVirtualClock::publish_progress(size_t cell) {
  PerCell& c = cells_[cell];
  ScanProgress m;
  m.header.stamp.fromNSec(c.last_scan_us * 1000);
  m.header.frame_id = c.frame_id;
  m.resets = resets_;
  m.scans = c.scans;
  m.inputs = c.inputs_received;
  m.scan_period.fromNSec(int64_t(c.period_us) * 1000);
  m.lag.fromNSec(int64_t(lag_us_) * 1000);
  m.fault = c.driver->host().cell().plc().locked([](ScanEngine& e, Memory&) { return e.fault(); });
  std::vector<uint64_t> counts;
  c.driver->host().count_published(&m.topics, &counts);
  m.published.assign(counts.begin(), counts.end());
  c.progress.publish(m);
}

}  // namespace plc_cell
