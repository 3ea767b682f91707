#!/usr/bin/python3
"""rostest: replaying a bag's clock and input topics into plc_node in virtual time
reproduces the recorded outputs bit for bit (values and stamps), on every kind of topic:
I/O, signals, register groups, counters, axes and temperatures. A recording of a real-time
cell's ~clock and stamped inputs replays too: the simulated sensor and the input's effect
come at the same times as they did live."""
import io
import math
import os
import subprocess
import sys
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

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import wait_until  # noqa: E402

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


class Changes(object):
    """(stamp ns, data) of each message on some Signal topics, and the clock's values with
    the time each arrived (what rosbag record keeps)."""

    def __init__(self, topics, clock=None):
        self.cond = threading.Condition()
        self.seen = {t: [] for t in topics}
        self.clock = []
        self.subs = [rospy.Subscriber(t, Signal, self._cb, t, queue_size=1000) for t in topics]
        if clock:
            self.subs.append(rospy.Subscriber(clock, Clock, self._clock, queue_size=1000))

    def _cb(self, m, topic):
        with self.cond:
            self.seen[topic].append((m.header.stamp.to_nsec(), m.data))
            self.cond.notify_all()

    def _clock(self, m):
        with self.cond:
            self.clock.append((m, rospy.Time.now()))
            self.cond.notify_all()

    def wait(self, pred):
        return wait_until(self.cond, pred, TIMEOUT)


class ReplayTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("replay_test", anonymous=True)

    def test_real_time_recording_replays(self):
        """The demo conveyor in real time: record its ~clock and a stamped stop_button
        message as rosbag record would (each at its arrival), play them into a
        virtual-time node: its cell starts where the live one did (the ~clock's first
        message, sent to every new subscriber), so the simulated part sensor changes at the
        live stamps, and the input, the recording's last, is scanned with its effect at
        the live stamp. Live stamps carry the real-time scan's jitter: 50 ms is allowed."""
        part, running = "signals_stamped/part_present", "signals_stamped/line_running"
        live = Changes(["/live/plc_node/" + part, "/live/plc_node/" + running], clock="/live/plc_node/clock")
        replay = Changes(["/live_replay/plc_node/" + part, "/live_replay/plc_node/" + running])
        stop = rospy.Publisher("/live/plc_node/inputs_stamped/stop_button", Signal, queue_size=10)
        for p in live.subs + replay.subs + [stop]:
            wait_connected(p)
        self.assertTrue(live.wait(lambda: len(live.clock) >= 2), "no ~clock from the real-time cell")
        origin = live.clock[0][0].clock.to_nsec()
        started = live.clock[-1][0].clock.to_nsec()  # the recording's first clock of now
        self.assertLess(origin, started)
        # The next change of the simulated part sensor (every 2.5 s) in the recording.
        self.assertTrue(live.wait(lambda: any(t > started for t, _ in live.seen["/live/plc_node/" + part])))
        part_live = [c for c in live.seen["/live/plc_node/" + part] if c[0] > started][0]
        press = Signal(data=False)  # the normally closed stop button, pressed
        press.header.stamp = rospy.Time.now()
        stop.publish(press)
        received = rospy.Time.now()
        self.assertTrue(live.wait(lambda: any(t >= press.header.stamp.to_nsec() and not on
                                              for t, on in live.seen["/live/plc_node/" + running])))
        stop_live = [t for t, on in live.seen["/live/plc_node/" + running] if t >= press.header.stamp.to_nsec()][0]
        # The recording ends 0.3 s after the input: more than the replay's lag.
        end = press.header.stamp.to_nsec() + 300000000
        self.assertTrue(live.wait(lambda: live.clock[-1][0].clock.to_nsec() > end))
        bag_path = os.path.join(tempfile.mkdtemp(), "live.bag")
        with rosbag.Bag(bag_path, "w") as bag:
            with live.cond:
                clock = list(live.clock)
            for c, t in clock:
                bag.write("/live/plc_node/clock", c, t)
            bag.write("/live/plc_node/inputs_stamped/stop_button", press, received)
        r = subprocess.run(["rosbag", "play", "--quiet", "--wait-for-subscribers", bag_path,
                            "__name:=live_player", "/live/plc_node/clock:=/live_replay/clock",
                            "/live/plc_node/inputs_stamped/stop_button:=/live_replay/plc_node/inputs_stamped/stop_button"],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=90)
        self.assertEqual(r.returncode, 0, r.stdout.decode(errors="replace"))
        tolerance = 50000000
        self.assertTrue(replay.wait(lambda: any(abs(t - stop_live) < tolerance and not on
                                                for t, on in replay.seen["/live_replay/plc_node/" + running])),
                        "the recorded input: live %d, replayed %s" % (stop_live, replay.seen["/live_replay/plc_node/" + running]))
        with replay.cond:
            parts = replay.seen["/live_replay/plc_node/" + part]
        self.assertTrue(any(abs(t - part_live[0]) < tolerance and on == part_live[1] for t, on in parts),
                        "the part sensor: live %s, replayed %s (origin %d)" % (part_live, parts, origin))
        self.assertLess(parts[0][0] - origin, 1000000, "the replayed cell starts at the live one's time 0")

    def test_replay_reproduces_outputs(self):
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
