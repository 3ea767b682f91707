#include "plc_cell/remote/remote_source.h"

#include <fstream>
#include <sstream>

#include "plc_cell/core/il_parser.h"
#include "plc_cell/io/transport.h"

namespace plc_cell {
namespace remote {

std::shared_ptr<const monitor::ProgramView> load_program_view(
    const std::string& path, const FunctionTable& functions, std::vector<std::pair<std::string, Address>> signals) {
  auto view = std::make_shared<monitor::ProgramView>();
  view->program = load_program_file(path, functions);  // throws SourceError with the place
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  view->text = text.str();
  view->file = path.substr(path.find_last_of('/') + 1);
  view->signals = std::move(signals);
  view->version = 1;
  return view;
}

RemoteSource::RemoteSource(std::unique_ptr<Link> link, std::shared_ptr<const monitor::ProgramView> program,
                           std::chrono::milliseconds retry_after)
    : link_(std::move(link)), describe_(link_->describe()), program_(std::move(program)), retry_after_(retry_after) {}

// Runs f on the link: refused at once while the link is down within the retry interval,
// and the link's state updated from how it went.
template <typename F>
auto RemoteSource::transact(const char* what, F&& f) -> decltype(f()) {
  std::lock_guard<std::mutex> line(link_mu_);
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    if (tried_ && !link_up_ && std::chrono::steady_clock::now() - failed_at_ < retry_after_)
      throw CommError(describe_ + ": link down: " + last_error_);
  }
  try {
    auto result = f();
    std::lock_guard<std::mutex> lk(state_mu_);
    tried_ = link_up_ = true;
    frames_ = link_->frames();
    return result;
  } catch (const CommError& e) {
    std::lock_guard<std::mutex> lk(state_mu_);
    tried_ = true;
    link_up_ = false;
    failed_at_ = std::chrono::steady_clock::now();
    last_error_ = std::string(what) + ": " + e.what();
    ++errors_;
    frames_ = link_->frames();
    throw CommError(describe_ + ": link down: " + last_error_);
  } catch (const Error& e) {  // the PLC refused (an error code): the link itself is up
    std::lock_guard<std::mutex> lk(state_mu_);
    tried_ = link_up_ = true;
    last_error_ = std::string(what) + ": " + e.what();
    ++errors_;
    frames_ = link_->frames();
    throw Error(describe_ + ": " + last_error_);
  }
}

monitor::Frame RemoteSource::read(const std::vector<Address>& addrs) {
  for (const Address& a : addrs) check_span(a, 1);  // throws naming the address
  monitor::Frame f;
  const auto t0 = std::chrono::steady_clock::now();
  transact("read", [&] {
    const std::optional<RunMode> m = link_->mode();
    f.values = addrs.empty() ? std::vector<uint32_t>{} : link_->read(addrs);
    f.mode = m.value_or(RunMode::Run);
    return 0;
  });
  const auto t1 = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lk(state_mu_);
  mode_ = f.mode;
  f.scan = ++polls_;  // a poll stands for a scan: the PLC's own scans are not seen
  f.t_us = uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(t1 - created_).count());
  poll_time_.add(uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count()));
  return f;
}

monitor::CellStatus RemoteSource::status() {
  monitor::CellStatus s;
  s.mode_switchable = link_->can_set_mode();
  s.engine = "";
  s.note = kRemoteNote;
  std::lock_guard<std::mutex> lk(state_mu_);
  s.mode = mode_;
  s.scan.scans = polls_;
  s.scan.cycle = poll_time_;  // the time a poll took on the line
  ServerStatus link;
  link.running = true;
  link.link_up = link_up_;
  link.requests = frames_;
  link.rejected = errors_;
  link.last_error = last_error_;
  s.servers.emplace_back(describe_, link);
  return s;
}

void RemoteSource::write(const Address& start, const std::vector<uint32_t>& values) {
  check_span(start, uint32_t(values.size()));
  transact("write", [&] {
    link_->write(start, values);
    return 0;
  });
}

void RemoteSource::force(const Address& bit, ForceAction action) {
  if (bit.width != Width::Bit || !is_discrete(bit.area))
    throw Error(format_address(bit) + ": only a single discrete is forced");
  transact("force", [&] {
    link_->force(bit, action);
    return 0;
  });
}

void RemoteSource::set_mode(RunMode mode) {
  transact(mode == RunMode::Run ? "run" : "stop", [&] {
    link_->set_run(mode == RunMode::Run);
    return 0;
  });
  std::lock_guard<std::mutex> lk(state_mu_);
  mode_ = mode;
}

uint64_t RemoteSource::frames() const {
  std::lock_guard<std::mutex> lk(state_mu_);
  return frames_;
}

}  // namespace remote
}  // namespace plc_cell
