#!/usr/bin/python3
"""Draws docs/img/motion_profiles.png: the closed-form profiles of docs/motion.md
(trapezoid, automatic triangle, separate deceleration, DRVC chain)."""
import math
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt


def plan(n, v_in, vt, v_out, a, d):
    """Segments (t0, v0, acc) of a move, the same equations as src/motion/profile.cpp."""
    vo = min(v_out, vt)
    d1 = abs(vt * vt - v_in * v_in) / (2 * (a if vt >= v_in else d))
    d3 = (vt * vt - vo * vo) / (2 * d)
    vc = vt
    if d1 + d3 > n:
        if v_out >= vt:
            vc = min(vt, math.sqrt(v_in * v_in + 2 * a * n))
        else:
            vc = min(vt, math.sqrt((2 * n * a * d + d * v_in ** 2 + a * vo ** 2) / (a + d)))
    vo = min(vo, vc)
    pts = [(0.0, v_in)]
    t = (vc - v_in) / a if vc >= v_in else (v_in - vc) / d
    pts.append((t, vc))
    cruise = n - abs(vc * vc - v_in * v_in) / (2 * (a if vc >= v_in else d)) - (vc * vc - vo * vo) / (2 * d)
    if cruise > 0:
        t += cruise / vc
        pts.append((t, vc))
    t += (vc - vo) / d
    pts.append((t, vo))
    return pts


A = 460000 / 0.1  # P4 / P8, P8 = 100 ms
F0 = 141
fig, ax = plt.subplots(2, 2, figsize=(11, 7))
cases = [
    ("trapezoid: 100000 Ps at 50 kHz", plan(100000, F0, 50000, F0, A, A)),
    ("triangle: 2000 Ps at 200 kHz (peak %.0f Hz)" % math.sqrt(F0 * F0 + 2000 * A), plan(2000, F0, 200000, F0, A, A)),
    ("P12 = P8/4: 20000 Ps at 100 kHz", plan(20000, F0, 100000, F0, A, 4 * A)),
]
for axis, (title, pts) in zip(ax.flat, cases):
    axis.plot([p[0] * 1000 for p in pts], [p[1] / 1000 for p in pts], "-o", ms=3)
    axis.set_title(title)
    axis.set_xlabel("t (ms)")
    axis.set_ylabel("f (kHz)")
    axis.grid(True)
# DRVC chain of the manual's example B: 20000 at 10 kHz, 60000 at 50 kHz, DRV 5000 at 3 kHz.
t0, v, xs, ys = 0.0, F0, [], []
for n, vt, last in [(20000, 10000, False), (60000, 50000, False), (5000, 3000, True)]:
    pts = plan(n, v, vt, F0 if last else vt, A, A)
    xs += [(t0 + p[0]) * 1000 for p in pts]
    ys += [p[1] / 1000 for p in pts]
    t0 += pts[-1][0]
    v = pts[-1][1]
ax.flat[3].plot(xs, ys, "-o", ms=3)
ax.flat[3].set_title("DRVC chain (manual example B)")
ax.flat[3].set_xlabel("t (ms)")
ax.flat[3].set_ylabel("f (kHz)")
ax.flat[3].grid(True)
fig.suptitle("FUN140 profiles: P4 = 460 kHz, P8 = 100 ms (slope 4.6 MHz/s), P5 = 141 Hz")
fig.tight_layout()
fig.savefig("docs/img/motion_profiles.png", dpi=90)
