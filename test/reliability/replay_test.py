#!/usr/bin/python3
"""rostest: replaying a bag's clock and input topics into plc_node in virtual time
reproduces the recorded outputs bit for bit (values and stamps), on every kind of topic:
I/O, signals, register groups, counters, axes and temperatures."""
import io
import math
import os
import subprocess
import tempfile
import threading
import time
import unittest

import rosbag
import rospy
import rostest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState, Temperature

from plc_cell.msg import AxisStatus, Counter, CounterArray, IoState, RegisterBlock, Signal

TIMEOUT = 20.0
T0 = 1000.0      # virtual start time, s
STEP = 0.01      # clock step, s
STEPS = 250
LAG = 0.5        # the nodes' ~virtual_time_lag
INPUTS = ["start", "part_present"]
OUTPUTS = [("io", IoState), ("signals_stamped/motor", Signal), ("signals_stamped/part_seen", Signal),
           ("registers/sums", RegisterBlock), ("counters", CounterArray), ("counters/belt", Counter),
           ("joint_states", JointState), ("motion/slide/status", AxisStatus),
           ("temperature/oven_temp", Temperature)]
# Published at a rate of virtual time (replay_cell.yaml, replay.test): period in ns.
PERIODIC = {"registers/sums": 20000000, "counters": 20000000, "counters/belt": 20000000,
            "joint_states": 20000000, "motion/slide/status": 20000000, "temperature/oven_temp": 100000000}


def zero_seq(msg):
    """The per-connection sequence numbers, in the message and the messages it holds."""
    if hasattr(msg, "seq") and hasattr(msg, "stamp"):
        msg.seq = 0
    for slot in getattr(msg, "__slots__", []):
        v = getattr(msg, slot)
        for m in (v if isinstance(v, list) else [v]):
            if hasattr(m, "__slots__"):
                zero_seq(m)


def key(msg):
    """What must be identical: the serialized message, stamps and values, bit for bit (a
    NaN temperature too), but not the per-connection sequence numbers."""
    zero_seq(msg)
    buf = io.BytesIO()
    msg.serialize(buf)
    return buf.getvalue()


def output_topic(ns, name):
    """joint_states is in the node's namespace (what a robot stack remaps), the rest private."""
    return "/%s/%s" % (ns, name) if name == "joint_states" else "/%s/plc_node/%s" % (ns, name)


class Collector(object):
    def __init__(self, ns):
        self.cond = threading.Condition()
        self.msgs = {name: [] for name, _ in OUTPUTS}
        self.subs = [rospy.Subscriber(output_topic(ns, name), t, self._cb, name, queue_size=10000)
                     for name, t in OUTPUTS]

    def _cb(self, msg, name):
        with self.cond:
            self.msgs[name].append(msg)
            self.cond.notify_all()

    def wait_for_stamp(self, name, stamp_ns):
        deadline = time.monotonic() + TIMEOUT
        with self.cond:
            while not any(m.header.stamp.to_nsec() >= stamp_ns for m in self.msgs[name]):
                left = deadline - time.monotonic()
                if left <= 0:
                    return False
                self.cond.wait(left)
        return True


def wait_connected(pub_or_sub):
    deadline = time.monotonic() + TIMEOUT
    while pub_or_sub.get_num_connections() == 0 and time.monotonic() < deadline:
        time.sleep(0.01)  # rospy has no event for "a connection is up"


class ReplayTest(unittest.TestCase):
    def test_replay_reproduces_outputs(self):
        rospy.init_node("replay_test", anonymous=True)
        rec = Collector("rec")
        replay = Collector("replay")
        clock = rospy.Publisher("/rec/clock", Clock, queue_size=1000)
        inputs = {n: rospy.Publisher("/rec/plc_node/inputs_stamped/" + n, Signal, queue_size=1000) for n in INPUTS}
        # Every output from the first scan on, so that both nodes are compared from there.
        for p in [clock] + list(inputs.values()) + rec.subs + replay.subs:
            wait_connected(p)
        bag_path = os.path.join(tempfile.mkdtemp(), "cell.bag")
        bag = rosbag.Bag(bag_path, "w")
        # Phase 1: drive /rec/plc_node and record what goes in and what comes out.
        level = {n: False for n in INPUTS}
        last_input_stamp = None
        for k in range(STEPS):
            now = rospy.Time.from_sec(T0 + k * STEP)
            c = Clock(clock=now)
            clock.publish(c)
            bag.write("/rec/clock", c, now)
            # Inputs at odd times between scans: start toggles every 17 steps, part every 29.
            for n, every in (("start", 17), ("part_present", 29)):
                if k % every == 5 and k < STEPS - 60:
                    level[n] = not level[n]
                    m = Signal(data=level[n])
                    m.header.stamp = rospy.Time.from_sec(T0 + k * STEP + 0.0037)
                    inputs[n].publish(m)
                    bag.write("/rec/plc_node/inputs_stamped/" + n, m, now)
                    last_input_stamp = m.header.stamp
            time.sleep(0.003)  # paces the clock (it is not waiting for a result)
        # Every scan up to the last input has run once its io message is out.
        self.assertTrue(rec.wait_for_stamp("io", last_input_stamp.to_nsec()))
        horizon = rospy.Time.from_sec(T0 + (STEPS - 1) * STEP - LAG).to_nsec()
        with rec.cond:
            recorded = {n: [m for m in rec.msgs[n] if m.header.stamp.to_nsec() <= horizon] for n in rec.msgs}
        for n, msgs in recorded.items():
            for m in msgs:
                bag.write("/rec/plc_node/" + n, m, m.header.stamp)
        bag.close()
        self.assertGreater(len(recorded["io"]), 10)
        self.assertGreater(len(recorded["signals_stamped/motor"]), 5)
        self.assertGreater(len(recorded["signals_stamped/part_seen"]), 1)
        # Rate groups in virtual time: one message per period of virtual time, on the scan
        # at the period's start (the scan period divides each).
        for n, period in PERIODIC.items():
            stamps = [m.header.stamp.to_nsec() for m in recorded[n]]
            self.assertGreater(len(stamps), 1.5e9 / period, n)
            self.assertEqual([t % period for t in stamps], [0] * len(stamps), n)
            self.assertEqual([b - a for a, b in zip(stamps, stamps[1:])], [period] * (len(stamps) - 1), n)
        # Each kind of topic follows the recorded inputs, else equal replays prove nothing:
        # the start input runs the motor, which turns the belt encoder and heats the oven, and
        # the slide's positioning table.
        counts = [m.counters[0].count for m in recorded["counters"]]
        self.assertEqual(counts, sorted(counts))
        self.assertGreater(counts[-1], counts[0])
        self.assertEqual([(m.header.stamp, m.header.frame_id, m.count) for m in recorded["counters/belt"]],
                         [(m.header.stamp, m.header.frame_id, m.counters[0].count) for m in recorded["counters"]])
        self.assertGreater(len({m.position[0] for m in recorded["joint_states"]}), 5)
        self.assertGreater(len({m.pulses for m in recorded["motion/slide/status"]}), 5)
        oven = {m.temperature for m in recorded["temperature/oven_temp"] if not math.isnan(m.temperature)}
        self.assertGreater(len(oven), 1)
        self.assertGreater(max(oven), 30.0)

        # Phase 2: rosbag play the inputs and the clock into /replay/plc_node.
        topics = ["/rec/clock"] + ["/rec/plc_node/inputs_stamped/" + n for n in INPUTS]
        remaps = ["/rec/clock:=/replay/clock"] + [
            "/rec/plc_node/inputs_stamped/%s:=/replay/plc_node/inputs_stamped/%s" % (n, n) for n in INPUTS]
        r = subprocess.run(["rosbag", "play", "--quiet", "--wait-for-subscribers", bag_path, "--topics"] + topics +
                           ["__name:=replay_player"] + remaps, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=90)
        self.assertEqual(r.returncode, 0, r.stdout.decode(errors="replace"))
        for n in ["io", "signals_stamped/motor"] + list(PERIODIC):
            self.assertTrue(replay.wait_for_stamp(n, recorded[n][-1].header.stamp.to_nsec()), n)

        # Outputs from the bag against the replay's, up to the same horizon.
        from_bag = {n: [] for n, _ in OUTPUTS}
        with rosbag.Bag(bag_path) as b:
            for topic, msg, _ in b.read_messages(topics=["/rec/plc_node/" + n for n, _ in OUTPUTS]):
                from_bag[topic[len("/rec/plc_node/"):]].append(key(msg))
        with replay.cond:
            got = {n: [key(m) for m in replay.msgs[n] if m.header.stamp.to_nsec() <= horizon] for n in replay.msgs}
        for n, _ in OUTPUTS:
            self.assertEqual(got[n], from_bag[n], n)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "replay_test", ReplayTest)
