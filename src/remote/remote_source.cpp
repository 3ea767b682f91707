#include "plc_cell/remote/remote_source.h"

#include <cstdio>

#include "plc_cell/core/file_text.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/io/transport.h"

namespace plc_cell {
namespace remote {

std::shared_ptr<const monitor::ProgramView> load_program_view(
    const std::string& path, const FunctionTable& functions, std::vector<std::pair<std::string, Address>> signals) {
  auto view = std::make_shared<monitor::ProgramView>();
  view->program = load_program_file(path, functions);  // throws SourceError with the place
  view->text = file_text(path).value_or("");
  view->file = path.substr(path.find_last_of('/') + 1);
  view->signals = std::move(signals);
  view->version = 1;
  return view;
}

namespace {

bool is_bit(const Address& a) { return is_discrete(a.area) && a.width == Width::Bit; }

// The discretes a program's contacts, coils and FUN operands name.
std::vector<Address> program_bits(const Program& p) {
  std::vector<Address> out;
  for (const Instruction& in : p.code) {
    const bool point = in.op <= Op::OrDown || (in.op >= Op::Out && in.op <= Op::Rst);
    if (point && in.op != Op::AndLd && in.op != Op::OrLd && is_bit(in.addr)) out.push_back(in.addr);
    for (const Operand& o : in.operands)
      if (o.kind == Operand::Kind::Bit && is_bit(o.addr)) out.push_back(o.addr);
  }
  return out;
}

std::string ms_text(double ns) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f ms", ns / 1e6);
  return b;
}

}  // namespace

RemoteSource::RemoteSource(std::unique_ptr<Link> link, std::shared_ptr<const monitor::ProgramView> program,
                           std::chrono::milliseconds retry_after, std::chrono::milliseconds forced_every)
    : link_(std::move(link)),
      describe_(link_->describe()),
      program_(std::move(program)),
      retry_after_(retry_after),
      forced_every_(forced_every) {
  for (const Address& a : program_bits(program_->program)) sweep_.emplace(key(a), a);
  for (const auto& signal : program_->signals)
    if (is_bit(signal.second)) sweep_.emplace(key(signal.second), signal.second);
  forced_readable_ = link_->no_forcing().empty();
}

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
    last_error_.clear();  // the link answers: an old error is history (the log keeps it)
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
    f.mode_known = m.has_value();
    f.mode = m.value_or(RunMode::Stop);
    sweep_forced(addrs);
    return 0;
  });
  const auto t1 = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lk(state_mu_);
  mode_ = f.mode;
  mode_known_ = f.mode_known;
  for (const Address& a : addrs) f.forced.push_back(is_bit(a) && forced_.count(key(a)));
  f.scan = ++polls_;  // a poll stands for a scan: the PLC's own scans are not seen
  f.t_us = uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(t1 - created_).count());
  poll_time_.add(uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count()));
  return f;
}

void RemoteSource::sweep_forced(const std::vector<Address>& addrs) {
  std::vector<Address> fresh;
  for (const Address& a : addrs)
    if (is_bit(a) && sweep_.emplace(key(a), a).second) fresh.push_back(a);
  const auto now = std::chrono::steady_clock::now();
  bool due;
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    if (!forced_readable_) return;
    due = !swept_ || now - swept_at_ >= forced_every_;
  }
  if (!due && fresh.empty()) return;
  std::vector<Address> bits = fresh;
  if (due) {
    bits.clear();
    for (const auto& kv : sweep_) bits.push_back(kv.second);
  }
  std::optional<std::vector<bool>> got;
  std::string refused;
  try {
    got = link_->forced(bits);
  } catch (const CommError&) {
    throw;  // the link is down: the read fails with it
  } catch (const Error& e) {
    refused = e.what();  // the PLC refused the question: its values are still good
  }
  std::lock_guard<std::mutex> lk(state_mu_);
  if (!got) {
    forced_readable_ = false;
    forced_error_ = refused;
    return;
  }
  if (due) forced_.clear();
  for (size_t i = 0; i < bits.size(); ++i)
    if ((*got)[i]) forced_.emplace(key(bits[i]), bits[i]);
    else forced_.erase(key(bits[i]));
  if (due) {
    swept_ = true;
    swept_at_ = now;
  }
  swept_count_ = sweep_.size();
}

std::string RemoteSource::forced_note() const {
  if (!link_->no_forcing().empty()) return "none can be: " + link_->no_forcing();
  if (!forced_readable_) return "not known: the PLC refused to tell (" + forced_error_ + ")";
  if (!swept_) return "not read yet";
  return "read from the PLC for the " + std::to_string(swept_count_) +
         " discretes the program and the pages name, all of them again every " +
         std::to_string(forced_every_.count()) + " ms";
}

monitor::CellStatus RemoteSource::status() {
  monitor::CellStatus s;
  s.mode_switchable = link_->can_set_mode();
  s.engine = "";
  s.note = kRemoteNote;
  s.scan_note = kRemoteScanNote;
  std::lock_guard<std::mutex> lk(state_mu_);
  s.mode = mode_;
  s.mode_known = tried_ && link_up_ && mode_known_;
  for (const auto& kv : forced_) s.forced.push_back(kv.second);
  s.forced_note = forced_note();
  // The polls' own figures, said to be the polls': a PLC's scan figures are not read.
  ExtensionStatus polling;
  polling.name = "polling";
  polling.level = tried_ && !link_up_ ? ExtensionStatus::Level::Error : ExtensionStatus::Level::Ok;
  polling.message = link_up_ ? "" : last_error_;
  polling.values = {{"polls", std::to_string(polls_)},
                    {"poll time avg", poll_time_.count ? ms_text(poll_time_.avg_ns()) : "–"},
                    {"poll time max", poll_time_.count ? ms_text(double(poll_time_.max_ns)) : "–"},
                    {"frames sent", std::to_string(frames_)},
                    {"failed transactions", std::to_string(errors_)}};
  s.extensions.push_back(std::move(polling));
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
    sweep_.emplace(key(bit), bit);
    return 0;
  });
  std::lock_guard<std::mutex> lk(state_mu_);  // known at once, before the next sweep reads it back
  if (action == ForceAction::Disable) forced_.emplace(key(bit), bit);
  if (action == ForceAction::Enable) forced_.erase(key(bit));
}

std::string RemoteSource::refusal(monitor::Change c) const {
  if (c == monitor::Change::Force) return link_->no_forcing();
  if (c == monitor::Change::Mode && !link_->can_set_mode()) return describe_ + " cannot switch RUN/STOP";
  return "";
}

uint64_t RemoteSource::now_us() {
  return uint64_t(
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - created_).count());
}

void RemoteSource::set_mode(RunMode mode) {
  transact(mode == RunMode::Run ? "run" : "stop", [&] {
    link_->set_run(mode == RunMode::Run);
    return 0;
  });
  std::lock_guard<std::mutex> lk(state_mu_);
  mode_ = mode;
  mode_known_ = true;  // as switched; the next poll reads it again where the PLC reports it
}

uint64_t RemoteSource::frames() const {
  std::lock_guard<std::mutex> lk(state_mu_);
  return frames_;
}

}  // namespace remote
}  // namespace plc_cell
