#pragma once
// A target that passes everything through and keeps a hash of what the case could see
// after every scan: the outputs Y0..Y255 and every probe the case reads. Two runs with the
// same hash showed the same values at every scan.
#include <cstdint>
#include <vector>

#include "plc_cell/mutation/mutation_run.h"
#include "plc_cell/scenario/target.h"

namespace plc_cell {
namespace mutation {

// The outputs of the subject's cells, 16 words each (WY0..WY240, named as the scenario
// names them: "robot.WY0" in a line).
std::vector<scenario::Probe> output_words(const Subject& s);
// name (a signal, an address) of one of the subject's cells as the scenario names it.
scenario::Probe probe_of(const Subject::Part& part, const std::string& name);
// Every probe c's steps and the file's properties read, each once (an analog input is
// driven, not read).
std::vector<scenario::Probe> case_probes(const scenario::Case& c);
// One scan's values of probes folded into hash.
uint64_t fold(uint64_t hash, scenario::Target& t, const std::vector<scenario::Probe>& probes);
constexpr uint64_t kHashStart = 1469598103934665603ULL;  // FNV-1a

class TracingTarget : public scenario::Target {
 public:
  // outputs: what is hashed besides the case's probes (output_words).
  TracingTarget(scenario::Target& inner, const scenario::Case& c, std::vector<scenario::Probe> outputs);
  uint64_t hash() const { return hash_; }

  uint64_t period_us() const override { return inner_.period_us(); }
  void scan(uint64_t t_us) override;
  std::string check(const scenario::Probe& p, bool writing) override { return inner_.check(p, writing); }
  scenario::Reading read(const scenario::Probe& p) override { return inner_.read(p); }
  void set(const scenario::Probe& p, const scenario::Value& v) override { inner_.set(p, v); }
  void write(const scenario::Probe& p, const scenario::Value& v) override { inner_.write(p, v); }
  void force(const scenario::Probe& p, bool on) override { inner_.force(p, on); }
  void release(const scenario::Probe* p) override { inner_.release(p); }
  void simulate(const scenario::Probe* p) override { inner_.simulate(p); }
  std::string label(const scenario::Probe& p) override { return inner_.label(p); }
  std::string fault() override { return inner_.fault(); }

 private:
  scenario::Target& inner_;
  std::vector<scenario::Probe> probes_;
  uint64_t hash_ = kHashStart;
};

}  // namespace mutation
}  // namespace plc_cell
