#!/usr/bin/python3
"""Plots the FUN86 oven test (test/temp/tpctl_test.cpp, Fun86Oven.ReachesAndHolds200)
from the trace it writes when PLC_CELL_OVEN_TRACE names a CSV file:

    PLC_CELL_OVEN_TRACE=/tmp/oven.csv temp_tests --gtest_filter=Fun86Oven.*
    scripts/plot_oven.py /tmp/oven.csv docs/oven.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    src, dst = sys.argv[1], sys.argv[2]
    t, plant, reading, out = [], [], [], []
    with open(src) as f:
        for row in csv.DictReader(f):
            t.append(float(row["t_s"]))
            plant.append(float(row["plant_c"]))
            reading.append(float(row["reading_c"]))
            out.append(100.0 * float(row["output"]) / 16383.0)
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(8, 6), gridspec_kw={"height_ratios": [3, 1]})
    ax1.plot(t, plant, label="oven (plant)")
    ax1.plot(t, reading, label="R0 reading (K TC, 0.1 degC)", linewidth=0.8)
    ax1.axhspan(199, 201, color="green", alpha=0.15, label="200 +- 1 degC")
    ax1.set_ylabel("degC")
    ax1.legend(loc="lower right")
    ax1.set_title("FUN86 TPCTL oven: 25 -> 200 degC (Kc 80, Ki 40, Td 20, Ts 4 s, PWM 2 s)")
    ax1.grid(True)
    ax2.plot(t, out, color="tab:red")
    ax2.set_ylabel("output %")
    ax2.set_xlabel("virtual time, s")
    ax2.grid(True)
    fig.tight_layout()
    fig.savefig(dst, dpi=90)


if __name__ == "__main__":
    main()
