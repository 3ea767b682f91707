#include "plc_cell/temp/fb_tc_scaling.h"

#include <cmath>

namespace plc_cell {
namespace temp {

int32_t fb_primitive(int32_t ir, int pl) { return fb_bipolar(pl) ? ir : ir + 2048; }

int32_t fb_tc_engineering(int32_t prim, int pl, double pos, double neg) {
  double v;
  if (prim >= 0)
    v = prim * (fb_bipolar(pl) ? 2.0 : 1.0) * pos / 1024.0;
  else
    v = prim * (fb_span10(pl) ? 2.0 : 1.0) * neg / 1024.0;  // negative only on bipolar spans
  return static_cast<int32_t>(std::lround(v));
}

int32_t fb_default_pos_factor(FbTc t, int pl, bool fun85) {
  const int32_t f = t == FbTc::K ? 248 : 240;
  return fun85 && !fb_span10(pl) ? f / 2 : f;
}

int32_t fb_default_neg_factor(FbTc t) { return t == FbTc::K ? 286 : 280; }

int32_t fb_line_broken_above(int pl) { return fb_span10(pl) ? 900 : 450; }

}  // namespace temp
}  // namespace plc_cell
