#include "plc_cell/ros/real_time_driver.h"

#include <ros/callback_queue_interface.h>
#include <rosgraph_msgs/Clock.h>

#include "plc_cell/core/error.h"
#include "plc_cell/core/realtime_loop.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {

namespace {
class FunctionCallback : public ros::CallbackInterface {
 public:
  explicit FunctionCallback(std::function<void()> fn) : fn_(std::move(fn)) {}
  CallResult call() override {
    fn_();
    return Success;
  }

 private:
  std::function<void()> fn_;
};
}  // namespace

RealTimeDriver::RealTimeDriver(ros::NodeHandle& nh, ros::NodeHandle& pnh, Host& host)
    : host_(host), queue_(nh.getCallbackQueue()) {
  double clock_rate = 10.0;
  pnh.param("clock_rate", clock_rate, clock_rate);
  pnh.param("shared_scan", shared_, shared_);
  pnh.param("shared_scan_threads", shared_threads_, shared_threads_);
  if (shared_threads_ < 1 || shared_threads_ > int(SharedScanThread::kMaxThreads))
    throw Error("~shared_scan_threads must be in [1, " + std::to_string(SharedScanThread::kMaxThreads) + "]");
  if (!(clock_rate >= 0 && clock_rate <= 1000)) throw Error("~clock_rate must be in [0, 1000] Hz (0: no ~clock)");
  if (clock_rate == 0) return;
  clock_rate_ = std::make_unique<VirtualRate>(clock_rate);
  // A recorder that connects after the start gets the cell's time 0 first: a bag of ~clock
  // then starts the replayed cell where this one started.
  clock_pub_ = pnh.advertise<rosgraph_msgs::Clock>("clock", 100, [this](const ros::SingleSubscriberPublisher& p) {
    const int64_t origin = origin_ns_;
    if (origin < 0) return;  // the first scan sends it
    rosgraph_msgs::Clock c;
    c.clock.fromNSec(uint64_t(origin));
    p.publish(c);
  });
}

RealTimeDriver::~RealTimeDriver() { queue_->removeByID(uint64_t(reinterpret_cast<uintptr_t>(this))); }

void RealTimeDriver::start() {
  Cell& cell = host_.cell();
  if (!shared_) return cell.start_scanning([this] { after_scan(); });
  shared_thread_ = &SharedScanThread::process(unsigned(shared_threads_));
  shared_id_ = shared_thread_->add(cell.plc(), std::chrono::microseconds(cell.scan_period_us()), [this] { after_scan(); },
                                   cell.rt_priority());
  const std::string refused = shared_thread_->priority_error();
  if (cell.rt_priority() > 0 && !refused.empty()) ROS_WARN("plc_node: ~rt_priority: %s", refused.c_str());
}

void RealTimeDriver::stop() {
  if (shared_id_) shared_thread_->remove(shared_id_);
  shared_id_ = 0;
}

void RealTimeDriver::input(TimedInput in) {
  host_.cell().plc().locked([&](ScanEngine& e, Memory&) {
    host_.apply(e, in);
    return 0;
  });
}

ros::Time RealTimeDriver::stamp(uint64_t cell_us) const {
  int64_t origin = origin_ns_;
  if (origin < 0) {  // the first scan: the cell's time 0 is now less its time
    origin = int64_t(ros::Time::now().toNSec()) - int64_t(cell_us) * 1000;
    origin_ns_ = origin;
  }
  ros::Time t;
  t.fromNSec(uint64_t(origin + int64_t(cell_us) * 1000));
  return t;
}

void RealTimeDriver::post(std::function<void()> fn) {
  queue_->addCallback(boost::make_shared<FunctionCallback>(std::move(fn)), uint64_t(reinterpret_cast<uintptr_t>(this)));
}

std::string RealTimeDriver::reset_refusal() const {
  return "~reset works in virtual time only (~virtual_time: true); restart plc_node for a fresh cell";
}

void RealTimeDriver::after_scan() {
  const uint64_t cell_us = host_.scanned();
  if (clock_rate_ && clock_rate_->due(cell_us)) post([this, cell_us] { publish_clock(cell_us); });
}

// ~clock: the ROS time of the cell's time 0 first, then of the scan at cell_us.
void RealTimeDriver::publish_clock(uint64_t cell_us) {
  std::lock_guard<std::mutex> lk(clock_mu_);
  rosgraph_msgs::Clock c;
  if (!clock_sent_) {
    c.clock = stamp(0);
    clock_pub_.publish(c);
    clock_sent_ = true;
  }
  c.clock = stamp(cell_us);
  clock_pub_.publish(c);
}

}  // namespace plc_cell
