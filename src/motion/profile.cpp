// Closed-form trapezoid/triangle profiles (equations in docs/motion.md).
#include "plc_cell/motion/profile.h"

#include <algorithm>
#include <cmath>

namespace plc_cell {
namespace motion {

namespace {
// Distance to change speed from u to w at rate r (0 for a step change).
double ramp_dist(double u, double w, double r) { return std::isinf(r) ? 0.0 : std::fabs(w * w - u * u) / (2 * r); }
double ramp_time(double u, double w, double r) { return std::isinf(r) ? 0.0 : std::fabs(w - u) / r; }
}  // namespace

void Profile::add(double dt, double v0, double a) {
  Segment s;
  if (!seg_.empty()) {
    const Segment& p = seg_.back();
    const double pdt = t_end_ - p.t0;
    s.t0 = t_end_;
    s.s0 = p.s0 + p.v0 * pdt + p.a * pdt * pdt / 2;
  }
  s.v0 = v0;
  s.a = a;
  seg_.push_back(s);
  t_end_ = s.t0 + dt;
  peak_ = std::max({peak_, v0, v0 + a * (std::isinf(dt) ? 0 : dt)});
}

Profile Profile::plan(int64_t n, double v_in, double vt, double v_out, double acc, double dec) {
  Profile p;
  p.n_ = n;
  const double rate1 = vt >= v_in ? acc : dec;
  if (n < 0) {  // endless: ramp to vt and cruise
    const double t1 = ramp_time(v_in, vt, rate1);
    if (t1 > 0) p.add(t1, v_in, vt > v_in ? acc : -dec);
    p.add(kInf, vt, 0);
    p.t_end_ = kInf;
    p.v_end_ = vt;
    return p;
  }
  const double N = static_cast<double>(n);
  double vc = vt;
  const double vo = std::min(v_out, vt);
  if (ramp_dist(v_in, vc, rate1) + ramp_dist(vc, vo, dec) > N) {
    if (vt > v_in && v_out >= vt) {
      // DRVC section: accelerate as far as the stroke allows, no stop.
      vc = std::isinf(acc) ? vt : std::min(vt, std::sqrt(v_in * v_in + 2 * acc * N));
    } else if (vt > v_in) {
      // Triangle: (vp^2 - v_in^2)/2a + (vp^2 - vo^2)/2d = N.
      double vp2;
      if (std::isinf(acc)) vp2 = vo * vo + 2 * dec * N;
      else if (std::isinf(dec)) vp2 = v_in * v_in + 2 * acc * N;
      else vp2 = (2 * N * acc * dec + dec * v_in * v_in + acc * vo * vo) / (acc + dec);
      vc = vp2 >= v_in * v_in ? std::min(vt, std::sqrt(vp2)) : -1;
    } else {
      vc = -1;
    }
    if (vc < 0) {
      // Slowing from v_in to vo needs more than the stroke: decelerate over the whole
      // stroke and end faster (the pulses stop there; documented).
      const double ve = std::sqrt(std::max(0.0, v_in * v_in - 2 * dec * N));
      p.add((v_in - ve) / dec, v_in, -dec);
      p.v_end_ = ve;
      p.peak_ = v_in;
      p.t_end_ = p.time_of(N);
      return p;
    }
  }
  const double vo2 = std::min(vo, vc);
  const double d1 = ramp_dist(v_in, vc, vc >= v_in ? acc : dec);
  const double t1 = ramp_time(v_in, vc, vc >= v_in ? acc : dec);
  if (t1 > 0) p.add(t1, v_in, vc > v_in ? acc : -dec);
  const double cruise = N - d1 - ramp_dist(vc, vo2, dec);
  if (cruise > 1e-9) p.add(cruise / vc, vc, 0);
  const double t3 = ramp_time(vc, vo2, dec);
  if (t3 > 0) p.add(t3, vc, -dec);
  if (p.seg_.empty()) p.add(N / vc, vc, 0);
  p.v_end_ = vo2;
  p.peak_ = std::max(p.peak_, vc);
  p.t_end_ = p.time_of(N);  // the same root the pulses use
  return p;
}

Profile Profile::stop(double v, double v_stop, double dec, int64_t n_limit) {
  v_stop = std::min(v_stop, v);
  double d = ramp_dist(v, v_stop, dec);
  int64_t n = static_cast<int64_t>(std::ceil(d - 1e-9));
  if (n < 1) n = v > 0 ? 1 : 0;
  if (n_limit >= 0) n = std::min(n, n_limit);
  Profile p;
  p.n_ = n;
  if (n == 0) return p;
  const double t1 = ramp_time(v, v_stop, dec);
  if (t1 > 0) p.add(t1, v, -dec);
  p.add(kInf, v_stop > 0 ? v_stop : v, 0);  // to the next whole pulse
  p.v_end_ = v_stop;
  p.t_end_ = p.time_of(static_cast<double>(n));
  return p;
}

Profile Profile::scaled(double k, int64_t n) const {
  Profile p = *this;
  p.n_ = n;
  for (auto& s : p.seg_) {
    s.s0 *= k;
    s.v0 *= k;
    s.a *= k;
  }
  p.peak_ *= k;
  p.v_end_ *= k;
  return p;  // t_end_ unchanged: every scaled axis ends on the lead axis's last pulse
}

double Profile::position(double t) const {
  if (seg_.empty() || t <= 0) return 0;
  if (!endless() && t >= t_end_) return static_cast<double>(n_);
  auto it = std::upper_bound(seg_.begin(), seg_.end(), t, [](double x, const Segment& s) { return x < s.t0; });
  const Segment& s = *(it - 1);
  const double dt = t - s.t0;
  const double x = s.s0 + s.v0 * dt + s.a * dt * dt / 2;
  return endless() ? x : std::min(x, static_cast<double>(n_));
}

double Profile::velocity(double t) const {
  if (seg_.empty() || t < 0 || (!endless() && t >= t_end_)) return 0;
  auto it = std::upper_bound(seg_.begin(), seg_.end(), t, [](double x, const Segment& s) { return x < s.t0; });
  const Segment& s = *(it - 1);
  return s.v0 + s.a * (t - s.t0);
}

double Profile::time_of(double x) const {
  if (x <= 0 || seg_.empty()) return 0;
  // Last segment whose start position is below x.
  size_t i = seg_.size();
  while (i > 1 && seg_[i - 1].s0 >= x) --i;
  const Segment& s = seg_[i - 1];
  const double d = x - s.s0;
  if (s.a == 0) return s.t0 + d / s.v0;
  const double disc = std::max(0.0, s.v0 * s.v0 + 2 * s.a * d);
  return s.t0 + 2 * d / (s.v0 + std::sqrt(disc));  // stable root of v0 t + a t^2/2 = d
}

int64_t Profile::emitted(double t) const {
  if (!endless() && t >= t_end_) return n_;
  const int64_t k = static_cast<int64_t>(std::floor(position(t) + 1e-9));
  return endless() ? k : std::min(k, n_);
}

}  // namespace motion
}  // namespace plc_cell
