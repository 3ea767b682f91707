#!/usr/bin/python3
"""Plots the axes of a bag of sensor_msgs/JointState (plc_node's joint_states, in m or
rad and m/s or rad/s): position and velocity of every joint over time, into a PNG.

    rosbag record -O run.bag /joint_states
    scripts/plot_motion.py run.bag -o run.png [--topic /joint_states]

Prints one summary line per joint (what test/ros/motion_plot_test.py checks):
    <name>: final position <p>, peak speed <|v| max>, <n> samples over <t> s
"""
import argparse
import collections

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import rosbag


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bag")
    ap.add_argument("-o", "--output", default="motion.png")
    ap.add_argument("--topic", default="/joint_states")
    args = ap.parse_args()
    t0 = None
    series = collections.OrderedDict()
    with rosbag.Bag(args.bag) as bag:
        for _, msg, _ in bag.read_messages(topics=[args.topic]):
            t = msg.header.stamp.to_sec()
            t0 = t if t0 is None else t0
            for i, name in enumerate(msg.name):
                s = series.setdefault(name, ([], [], []))
                s[0].append(t - t0)
                s[1].append(msg.position[i] if i < len(msg.position) else float("nan"))
                s[2].append(msg.velocity[i] if i < len(msg.velocity) else float("nan"))
    if not series:
        raise SystemExit("no %s messages in %s" % (args.topic, args.bag))
    fig, (ax_p, ax_v) = plt.subplots(2, 1, sharex=True, figsize=(9, 6))
    for name, (t, p, v) in series.items():
        ax_p.plot(t, p, label=name)
        ax_v.plot(t, v, label=name)
    ax_p.set_ylabel("position (m or rad)")
    ax_v.set_ylabel("velocity (m/s or rad/s)")
    ax_v.set_xlabel("t (s)")
    for a in (ax_p, ax_v):
        a.grid(True)
        a.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=90)
    print("wrote %s (%d joints)" % (args.output, len(series)))
    for name, (t, p, v) in series.items():
        print("%s: final position %.6g, peak speed %.6g, %d samples over %.3f s"
              % (name, p[-1], max(abs(x) for x in v), len(t), t[-1] - t[0]))


if __name__ == "__main__":
    main()
