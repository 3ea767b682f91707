#!/usr/bin/python3
"""Plots an oven run: the temperature reading against its set point, and the heater output.

It reads any of the three records a run leaves:

* a `plc_cell sim --trace` CSV (columns time_s,address,value; one row per change):
      plc_cell sim --config examples/oven/oven.yaml --duration 1800s --watch R0,R200 --trace oven.csv
      scripts/plot_oven.py oven.csv oven.png
  The reading register (--reading, default R0) is in 0.1 degC; the output register
  (--output, default R200) is FUN86's output, 0..16383 full scale.
* a bag of plc_node's sensor_msgs/Temperature topic (--topic, default
  /plc_node/temperature/oven_temp) and, if recorded, the output's register group
  (--output-topic, a plc_cell/RegisterBlock whose first value is the output):
      rosbag record -O oven.bag /plc_node/temperature/oven_temp
      scripts/plot_oven.py oven.bag oven.png
* the trace of the FUN86 oven gtest (columns t_s,plant_c,reading_c,output), written when
  PLC_CELL_OVEN_TRACE names a file.

It prints one summary line: samples, final reading, peak, and the last time the reading
left set point +- band (the settling time)."""
import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FULL_SCALE = 16383.0


def read_trace(path, reading, output):
    t, temp, ot, out = [], [], [], []
    with open(path) as f:
        for row in csv.DictReader(f):
            if row["address"] == reading:
                t.append(float(row["time_s"]))
                temp.append(int(row["value"]) / 10.0)
            elif row["address"] == output:
                ot.append(float(row["time_s"]))
                out.append(100.0 * int(row["value"]) / FULL_SCALE)
    if not t:
        raise SystemExit("%s: no rows for %s (record it with --watch %s)" % (path, reading, reading))
    return t, temp, ot, out, None


def read_gtest(path):
    t, plant, temp, out = [], [], [], []
    with open(path) as f:
        for row in csv.DictReader(f):
            t.append(float(row["t_s"]))
            plant.append(float(row["plant_c"]))
            temp.append(float(row["reading_c"]))
            out.append(100.0 * float(row["output"]) / FULL_SCALE)
    return t, temp, t, out, plant


def read_bag(path, topic, output_topic):
    import rosbag  # only for bags: the CSV forms need no ROS
    t, temp, ot, out = [], [], [], []
    t0 = None
    with rosbag.Bag(path) as bag:
        for name, msg, stamp in bag.read_messages(topics=[topic, output_topic] if output_topic else [topic]):
            s = msg.header.stamp.to_sec() if msg.header.stamp.to_sec() > 0 else stamp.to_sec()
            t0 = s if t0 is None else t0
            if name == topic:
                t.append(s - t0)
                temp.append(msg.temperature)
            else:
                ot.append(s - t0)
                out.append(100.0 * msg.values[0] / FULL_SCALE)
    if not t:
        raise SystemExit("%s: no messages on %s" % (path, topic))
    return t, temp, ot, out, None


def settled_after(t, temp, setpoint, band):
    """The first time after which the reading stays within setpoint +- band (None if never)."""
    last_out = None
    for ti, v in zip(t, temp):
        if abs(v - setpoint) > band:
            last_out = ti
    if last_out is None:
        return t[0]
    later = [ti for ti in t if ti > last_out]
    return later[0] if later else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("input", help="a plc_cell sim --trace CSV, a .bag, or the oven gtest's CSV")
    ap.add_argument("png")
    ap.add_argument("--reading", default="R0", help="trace: the reading register (0.1 degC)")
    ap.add_argument("--output", default="R200", help="trace: the output register (0..16383)")
    ap.add_argument("--topic", default="/plc_node/temperature/oven_temp")
    ap.add_argument("--output-topic", default="")
    ap.add_argument("--setpoint", type=float, default=200.0)
    ap.add_argument("--band", type=float, default=1.0)
    a = ap.parse_args()

    if a.input.endswith(".bag"):
        t, temp, ot, out, plant = read_bag(a.input, a.topic, a.output_topic)
    else:
        with open(a.input) as f:
            header = f.readline().strip().split(",")
        if header[:3] == ["time_s", "address", "value"]:
            t, temp, ot, out, plant = read_trace(a.input, a.reading, a.output)
        elif header[:2] == ["t_s", "plant_c"]:
            t, temp, ot, out, plant = read_gtest(a.input)
        else:
            raise SystemExit("%s: not a plc_cell sim --trace CSV (time_s,address,value) nor the oven test's CSV"
                             % a.input)

    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(8, 6), gridspec_kw={"height_ratios": [3, 1]})
    if plant:
        ax1.plot(t, plant, label="oven (plant)")
    ax1.step(t, temp, where="post", label="reading", linewidth=0.8)
    ax1.axhspan(a.setpoint - a.band, a.setpoint + a.band, color="green", alpha=0.15,
                label="%g +- %g degC" % (a.setpoint, a.band))
    ax1.set_ylabel("degC")
    ax1.legend(loc="lower right")
    ax1.grid(True)
    if out:
        ax2.step(ot, out, where="post", color="tab:red")
    ax2.set_ylabel("output %")
    ax2.set_xlabel("time, s")
    ax2.grid(True)
    fig.tight_layout()
    fig.savefig(a.png, dpi=90)
    settle = settled_after(t, temp, a.setpoint, a.band)
    print("%d samples, final %.1f degC, peak %.1f degC, within %g +- %g from %s" % (
        len(t), temp[-1], max(temp), a.setpoint, a.band, "never" if settle is None else "%.1f s" % settle))


if __name__ == "__main__":
    main()
