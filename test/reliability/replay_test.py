#!/usr/bin/python3
"""rostest: replaying a bag's clock and input topics into plc_node in virtual time
reproduces the recorded outputs bit for bit (values and stamps)."""
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

from plc_cell.msg import IoState, RegisterBlock, Signal

TIMEOUT = 20.0
T0 = 1000.0      # virtual start time, s
STEP = 0.01      # clock step, s
STEPS = 250
LAG = 0.5        # the nodes' ~virtual_time_lag
INPUTS = ["start", "part_present"]
OUTPUTS = [("io", IoState), ("signals_stamped/motor", Signal), ("signals_stamped/part_seen", Signal),
           ("registers/sums", RegisterBlock)]  # test_cell.yaml: 50 Hz of virtual time


def key(msg):
    """What must be identical: stamps and values (not the per-connection sequence number)."""
    if hasattr(msg, "x"):  # IoState (a bag gives its own generated class)
        return (msg.header.stamp.to_nsec(), msg.run, tuple(msg.x), tuple(msg.y))
    if hasattr(msg, "values"):  # RegisterBlock
        return (msg.header.stamp.to_nsec(), tuple(msg.values))
    return (msg.header.stamp.to_nsec(), msg.data)


class Collector(object):
    def __init__(self, ns):
        self.cond = threading.Condition()
        self.msgs = {name: [] for name, _ in OUTPUTS}
        self.subs = [rospy.Subscriber("/%s/plc_node/%s" % (ns, name), t, self._cb, name, queue_size=10000)
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


def wait_connected(pub):
    deadline = time.monotonic() + TIMEOUT
    while pub.get_num_connections() == 0 and time.monotonic() < deadline:
        time.sleep(0.01)  # rospy has no event for "a subscriber connected"


class ReplayTest(unittest.TestCase):
    def test_replay_reproduces_outputs(self):
        rospy.init_node("replay_test", anonymous=True)
        rec = Collector("rec")
        replay = Collector("replay")
        clock = rospy.Publisher("/rec/clock", Clock, queue_size=1000)
        inputs = {n: rospy.Publisher("/rec/plc_node/inputs_stamped/" + n, Signal, queue_size=1000) for n in INPUTS}
        for p in [clock] + list(inputs.values()):
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
        # A register group in virtual time: one block per 20 ms of virtual time, on its scan.
        sums = [m.header.stamp.to_nsec() for m in recorded["registers/sums"]]
        self.assertGreater(len(sums), 50)
        self.assertEqual([t % 20000000 for t in sums], [0] * len(sums))
        self.assertEqual([b - a for a, b in zip(sums, sums[1:])], [20000000] * (len(sums) - 1))

        # Phase 2: rosbag play the inputs and the clock into /replay/plc_node.
        topics = ["/rec/clock"] + ["/rec/plc_node/inputs_stamped/" + n for n in INPUTS]
        remaps = ["/rec/clock:=/replay/clock"] + [
            "/rec/plc_node/inputs_stamped/%s:=/replay/plc_node/inputs_stamped/%s" % (n, n) for n in INPUTS]
        r = subprocess.run(["rosbag", "play", "--quiet", "--wait-for-subscribers", bag_path, "--topics"] + topics +
                           ["__name:=replay_player"] + remaps, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=90)
        self.assertEqual(r.returncode, 0, r.stdout.decode(errors="replace"))
        for n in ("io", "signals_stamped/motor"):
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
