#include "plc_cell/runtime/cell.h"

#include <algorithm>

#include "plc_cell/comm/protocol_functions.h"
#include "plc_cell/core/error.h"
#include "plc_cell/sim/lockstep_cells.h"
#include "plc_cell/temp/rtc.h"

namespace plc_cell {
namespace {

// The last override of key, checked against its spec (every override is checked);
// nullptr when none.
const std::string* run_value(const std::vector<SettingOverride>& run, const std::string& key,
                             std::string* checked) {
  const std::string* out = nullptr;
  for (const auto& o : run) {
    const auto& specs = Cell::run_settings();
    const auto s = std::find_if(specs.begin(), specs.end(), [&](const SettingSpec& x) { return x.key == o.key; });
    if (s == specs.end()) throw Error(o.origin + ": no run setting '" + o.key + "'");
    if (o.key != key) continue;
    if (o.values.size() != 1) throw Error(o.origin + ": takes one value");
    try {
      *checked = check_setting(*s, o.values[0]);
    } catch (const Error& e) {
      throw Error(o.origin + " " + o.values[0] + ": " + e.what());
    }
    out = checked;
  }
  return out;
}

// Where the last override of key came from ("--engine", "~engine").
std::string origin_of(const std::vector<SettingOverride>& run, const std::string& key) {
  const auto at = std::find_if(run.rbegin(), run.rend(), [&](const SettingOverride& x) { return x.key == key; });
  return at == run.rend() ? key : at->origin;
}

// Virtual time unless served in real time; the calendar's start as rtc_start says.
CellClock cell_clock(const CellOverrides& o, Cell::Purpose purpose) {
  CellClock c;
  c.virtual_time = purpose != Cell::Purpose::Serve || o.virtual_time;
  std::string v;
  if (const std::string* start = run_value(o.run, "rtc_start", &v)) {
    const std::string why = temp::calendar_start_problem(*start);
    if (!why.empty()) throw Error(origin_of(o.run, "rtc_start") + " " + *start + ": " + why);
    c.calendar_start = *start;
  }
  return c;
}

// The servers: section, read with the cell's other sections so that its errors are listed
// with theirs; the servers themselves are made once the overrides are merged.
class ServerSettingsSection : public CellExtension {
 public:
  explicit ServerSettingsSection(const std::vector<ServerKind>& kinds) : kinds_(kinds) {}
  std::string name() const override { return "servers"; }
  std::vector<std::string> sections() const override { return {"servers"}; }
  void attach(const CellConfig& cfg, Plc&, ErrorList& errors) override {
    const YAML::Node at = cfg.document.IsMap() ? cfg.document["servers"] : YAML::Node();
    errors.collect([&] { merge_server_settings(kinds_, cfg); }, cfg.file, at);
  }
  void detach(Plc&) override {}

 private:
  const std::vector<ServerKind>& kinds_;
};

// What a Cell adds to the built-in extensions: FUN150/151 with their ports (opened unless
// the cell is only checked) and the servers' section.
CellExtensions runtime_extensions(Cell::Purpose purpose) {
  CellExtensions more;
  more.push_back(std::make_unique<ProtocolFunctions>(purpose != Cell::Purpose::Check));
  more.push_back(std::make_unique<ServerSettingsSection>(Cell::server_kinds()));
  return more;
}

}  // namespace

std::set<std::string> Cell::sections() { return SoftCell::sections(runtime_extensions(Purpose::Check)); }

const std::vector<SettingSpec>& Cell::run_settings() {
  // The bounds are the YAML's (plc.scan_period, plc.persist.interval): a value refused in
  // the file is refused as an option or a parameter too.
  static const std::vector<SettingSpec> specs = {
      duration_setting("scan_period", "", 100, 1000000, "scan period (default plc.scan_period)"),
      integer_setting("rt_priority", 0, 0, 99, "SCHED_FIFO priority of the scan thread, 0 = normal"),
      setting("persist_file", SettingType::Text, "retentive store (default plc.persist.file)"),
      duration_setting("persist_interval", "", 1000, 60000000, "store flush interval (default plc.persist.interval)"),
      setting("engine", SettingType::Text, "native, interpreter or lockstep (default plc.engine)"),
      setting("rtc_start", SettingType::Text,
              "the RTC's start, a date-time or host (default modules.rtc.start, else 2024-01-01T00:00:00 in "
              "virtual time and the host's local time in real time)"),
  };
  return specs;
}

Cell::Cell(const std::string& config_path, const CellOverrides& o, Purpose purpose,
           std::function<void(const std::string&)> log) {
  const auto& kinds = server_kinds();
  const CellClock clock = cell_clock(o, purpose);
  soft_ = std::make_unique<SoftCell>(config_path, o.program, runtime_extensions(purpose), clock);
  const CellConfig& cfg = soft_->config();
  server_settings_ = merge_server_settings(kinds, cfg, o.servers);

  std::string v;
  scan_us_ = run_value(o.run, "scan_period", &v) ? parse_duration_us(v) : cfg.scan_period_us;
  rt_priority_ = run_value(o.run, "rt_priority", &v) ? std::stoi(v) : 0;
  persist_ = cfg.persist;
  if (run_value(o.run, "persist_file", &v)) persist_.file = v;  // "" turns the store off
  if (run_value(o.run, "persist_interval", &v)) persist_.interval_us = parse_duration_us(v);
  EngineChoice engine = cfg.engine;
  if (const std::string* e = run_value(o.run, "engine", &v); e && !parse_engine_choice(*e, &engine))
    throw Error(origin_of(o.run, "engine") + " " + *e + ": expected native, interpreter or lockstep");
  if (engine == EngineChoice::Lockstep) {
    run_in_lockstep(config_path, o, clock);
  } else {
    plc().locked([&](ScanEngine& se, Memory&) {
      se.set_engine(engine);
      return 0;
    });
  }

  online::ChangeSetup change;
  change.cell_file = config_path;
  change.program_path = soft_->program_path();
  if (const auto* gate = soft_->get<GateConfig>()) change.gate = *gate;
  change.extensions = &soft_->extensions();
  changes_ = std::make_unique<online::ChangeService>(plc(), change);

  ServerContext context(plc());
  context.changes = changes_.get();
  context.config = &cfg;
  context.extensions = &soft_->extensions();
  context.program_path = soft_->program_path();
  context.servers = [this] {
    std::vector<const Server*> out;
    for (const auto& s : servers_) out.push_back(s.get());
    return out;
  };
  for (const auto& k : kinds)
    for (auto& s : k.make(context, server_settings_.at(k.name))) servers_.push_back(std::move(s));
  // Retentive memory from the last run, before the first scan and the first request.
  if (purpose == Purpose::Serve && !persist_.file.empty())
    persister_ = std::make_unique<persist::Persister>(plc(), persist_, std::move(log));
}

// The twin is the same cell built again, FUN150/151 with no port (one line has one owner):
// a program that talks on the cell's COM ports cannot run twice, and is refused.
void Cell::run_in_lockstep(const std::string& config_path, const CellOverrides& o, const CellClock& clock) {
  for (const auto& x : soft_->extensions())
    if (x->name() == "protocol functions" && !x->status(plc()).empty())
      throw Error("lockstep: the cell's FUN150/FUN151 own its COM ports (ports:), which its interpreter twin "
                  "cannot share; run it on one engine");
  twin_ = std::make_unique<SoftCell>(config_path, soft_->program_path(), runtime_extensions(Purpose::Check), clock);
  plc_cell::run_in_lockstep(*soft_, *twin_);
}

Cell::~Cell() { stop(); }

void Cell::start_servers(const std::function<void(const Server&)>& served) {
  for (auto& s : servers_) {
    s->start();
    if (served) served(*s);
  }
}

void Cell::start_scanning(std::function<void()> after_scan) {
  loop_ = std::make_unique<RealTimeLoop>(plc(), std::chrono::microseconds(scan_us_));
  if (after_scan) loop_->set_after_scan(std::move(after_scan));
  loop_->set_priority(rt_priority_);
  loop_->start();
}

void Cell::stop() {
  for (auto& s : servers_) s->stop();
  if (loop_) loop_->stop();
  persister_.reset();  // after every writer stopped: the newest image goes to disk
}

}  // namespace plc_cell
