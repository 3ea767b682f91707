#pragma once
// The Edit tab's side of the API (docs/monitor-api.md, "Program changes"): the running
// program's text, a new text checked with its errors at their lines and the networks that
// changed drawn old beside new, and the gate, Apply and Undo of the cell's change service
// (config/program_changes.h) as jobs on a thread of their own, so that a gate that takes a
// second holds up no page's frames. The page polls a job until it is done.
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "plc_cell/config/program_changes.h"
#include "plc_cell/monitor/source.h"

namespace plc_cell {
namespace monitor {

class EditDesk {
 public:
  // apply_refusal: why a page may not apply here ("" = it may): the server's edit setting.
  EditDesk(Source& source, std::string apply_refusal, std::function<void(const std::string&)> log);
  ~EditDesk();

  // GET /api/edit: what the tab shows first.
  nlohmann::json state() const;
  // POST /api/edit/check {"text"}: errors, refusals, diff and the changed networks.
  nlohmann::json check(const std::string& text) const;
  // POST /api/edit/{test,apply,undo}: starts the job, or says why not (Error).
  nlohmann::json start(const std::string& what, const nlohmann::json& body);
  // GET /api/edit/job: the last job, running or done.
  nlohmann::json job() const;
  nlohmann::json log(size_t last) const;

 private:
  ProgramChanges& changes() const;
  void run(const std::string& what, std::function<nlohmann::json()> work);

  Source& source_;
  std::string apply_refusal_;
  std::function<void(const std::string&)> log_;
  mutable std::mutex mu_;
  uint64_t job_id_ = 0;
  bool running_ = false;
  std::string job_what_;
  nlohmann::json job_result_;
  std::thread worker_;
};

// The networks that differ between two layouts (GET /api/ladder's form), paired old beside
// new in program order: [{"old": network|null, "new": network|null}]. A network's identity
// is its IL without comments and spacing.
nlohmann::json changed_networks(const nlohmann::json& old_layout, const nlohmann::json& new_layout);

}  // namespace monitor
}  // namespace plc_cell
