#!/usr/bin/python3
"""rostest: bag of plc_node's JointState while it runs the manual's example B (DRVC
chain 10 kHz x 20000, 50 kHz x 60000, 3 kHz x 5000 pulses), then
scripts/plot_motion.py on it: the PNG exists and the printed summary gives the final
position 0.85 m and the peak speed 0.5 m/s (85000 pulses, 50 kHz at 10 um per pulse)."""
import os
import re
import subprocess
import sys
import tempfile
import threading
import unittest

import rosbag
import rospy
import rostest
from sensor_msgs.msg import JointState
from std_srvs.srv import SetBool

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import Latest  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
PLOT = os.path.join(HERE, "..", "..", "scripts", "plot_motion.py")
TOPIC = "/joint_states"  # the node's namespace, in SI units
# Manual 11.6 example B: 20000 + 60000 + 5000 pulses; the fastest section is SPD 50000;
# si_per_pulse 0.00001 (examples/motion/drvc_chain.yaml).
FINAL = 0.85
PEAK = 0.5
RUN_TIMEOUT = 30.0  # the chain takes about 5.6 s of real time


class Recorder(object):
    """Writes every JointState into a bag as it arrives."""

    def __init__(self, path):
        self.bag = rosbag.Bag(path, "w")
        self.lock = threading.Lock()
        self.count = 0
        self.sub = rospy.Subscriber(TOPIC, JointState, self._cb, queue_size=1000)

    def _cb(self, msg):
        with self.lock:
            if self.bag is not None:
                self.bag.write(TOPIC, msg, msg.header.stamp)
                self.count += 1

    def close(self):
        self.sub.unregister()
        with self.lock:
            self.bag.close()
            self.bag = None


class MotionPlotTest(unittest.TestCase):
    def test_bag_to_png(self):
        tmp = tempfile.mkdtemp(prefix="motion_plot_")
        bag_path = os.path.join(tmp, "example_b.bag")
        png = rospy.get_param("~png", "") or os.path.join(tmp, "example_b.png")
        latest = Latest(TOPIC, JointState, timeout=RUN_TIMEOUT)
        # plc_node is in STOP (autostart false): the JointState stream shows the axis at 0.
        first = latest.wait_for(lambda m: len(m.position) == 1)
        self.assertIsNotNone(first, "no JointState from plc_node")
        self.assertEqual(first.position[0], 0.0)
        rec = Recorder(bag_path)
        latest.wait_for(lambda m: rec.count > 0)  # the recorder sees the stream too
        rospy.wait_for_service("/plc_node/set_run_mode", RUN_TIMEOUT)
        self.assertTrue(rospy.ServiceProxy("/plc_node/set_run_mode", SetBool)(True).success)
        done = latest.wait_for(lambda m: abs(m.position[0] - FINAL) < 1e-12 and m.velocity[0] == 0.0)
        self.assertAlmostEqual(done.position[0], FINAL, 12, "the chain did not reach 0.85 m in %.0f s" % RUN_TIMEOUT)
        n = rec.count
        latest.wait_for(lambda m: rec.count >= n + 5)  # a few samples of the rest
        rec.close()

        out = subprocess.check_output([sys.executable, PLOT, bag_path, "-o", png], universal_newlines=True)
        self.assertTrue(os.path.getsize(png) > 10000, "PNG missing or empty: %s" % png)
        m = re.search(r"feed: final position (\S+), peak speed (\S+), (\d+) samples", out)
        self.assertIsNotNone(m, out)
        self.assertEqual(float(m.group(1)), FINAL)  # printed with 6 digits
        # JointState samples the cruise at 50 kHz (1.2 s long, sampled at 50 Hz).
        self.assertEqual(float(m.group(2)), PEAK)
        self.assertGreater(int(m.group(3)), 100)


if __name__ == "__main__":
    rospy.init_node("motion_plot_test")
    rostest.rosrun("plc_cell", "motion_plot_test", MotionPlotTest)
