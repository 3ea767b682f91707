#pragma once
// Coverage of a run over several programs (test files for different cells): one Recorder
// per program file, picked by the program each PLC has loaded when it is attached.
#include <map>
#include <string>
#include <vector>

#include "plc_cell/coverage/recorder.h"

namespace plc_cell {
namespace coverage {

class Recorders {
 public:
  // The recorder of plc's program file, made on its first use, attached to plc. Throws as
  // Recorder::attach does: a file whose instructions changed between two PLCs is refused.
  Recorder& attach(Plc& plc, const SignalNames& names = {});
  // Detaches plc from whichever recorder holds it; safe twice.
  void detach(Plc& plc);
  // One report per program recorded, in file-name order.
  std::vector<Report> reports() const;

 private:
  std::map<std::string, Recorder> by_file_;
};

}  // namespace coverage
}  // namespace plc_cell
