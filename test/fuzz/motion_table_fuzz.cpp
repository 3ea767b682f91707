// Any motion-table text (FUN140 and FUN147, as written by users and sent by HMIs) and any register
// image of a table (written over FATEK or Modbus): the parser and the decoder either
// accept it or report an error code; an accepted table survives encode -> decode.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "plc_cell/motion/lin_table.h"
#include "plc_cell/motion/table.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace plc_cell::motion;
  Table t;
  TableError err;
  if (parse_table(std::string(reinterpret_cast<const char*>(data), size), &t, &err)) {
    const std::vector<uint16_t> regs = encode_table(t);
    Table back;
    if (!decode_table(regs.data(), regs.size(), &back, &err)) std::abort();  // our own encoding must decode
    if (encode_table(back) != regs) std::abort();
  }
  LinTable lt;
  if (parse_lin_table(std::string(reinterpret_cast<const char*>(data), size), &lt, &err)) {
    const std::vector<uint16_t> regs = encode_lin_table(lt);
    LinTable back;
    if (!decode_lin_table(regs.data(), regs.size(), &back, &err)) std::abort();
    if (encode_lin_table(back) != regs) std::abort();
  }
  std::vector<uint16_t> words(size / 2);
  for (size_t i = 0; i < words.size(); ++i) words[i] = uint16_t(data[2 * i] | (data[2 * i + 1] << 8));
  Table any;
  (void)decode_table(words.data(), words.size(), &any, &err);
  LinTable any_lin;
  (void)decode_lin_table(words.data(), words.size(), &any_lin, &err);
  return 0;
}
