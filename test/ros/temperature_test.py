#!/usr/bin/python3
"""rostest for plc_node's temperature topics, module diagnostics and ~set_pid_loop."""
import math
import os
import sys
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from sensor_msgs.msg import Temperature

from plc_cell.msg import RegisterBlock
from plc_cell.srv import ReadMemory, SetPidLoop

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import Latest  # noqa: E402

NS = "/plc_node/"
TIMEOUT = 15.0




def module_status(arr, name):
    for s in arr.status:
        if name in s.name:
            return s
    return None


class TemperatureTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("temperature_test", anonymous=True)
        for s in ["read", "set_pid_loop"]:
            rospy.wait_for_service(NS + s, timeout=30)
        cls.read = rospy.ServiceProxy(NS + "read", ReadMemory)
        cls.set_loop = rospy.ServiceProxy(NS + "set_pid_loop", SetPidLoop)
        cls.oven = Latest(NS + "temperature/oven_temp", Temperature, timeout=TIMEOUT)
        cls.broken = Latest(NS + "temperature/broken", Temperature, timeout=TIMEOUT)
        cls.room = Latest(NS + "temperature/room", Temperature, timeout=TIMEOUT)
        cls.diag = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)

    def test_channels(self):
        room = self.room.wait_for(lambda m: not math.isnan(m.temperature))
        self.assertIsNotNone(room)
        self.assertEqual(room.header.frame_id, "")  # no ~frame_id: a channel name is no frame
        self.assertAlmostEqual(room.temperature, 21.5, places=6)
        self.assertAlmostEqual(room.variance, 0.01 / 12, places=9)  # 0.1 degC steps
        oven = self.oven.wait_for(lambda m: not math.isnan(m.temperature))
        self.assertEqual(oven.header.frame_id, "")
        self.assertGreaterEqual(oven.temperature, 24.9)
        self.assertLess(oven.temperature, 60.0)

    def test_open_circuit_is_nan(self):
        m = self.broken.wait_for(lambda m: True)
        self.assertIsNotNone(m)
        self.assertEqual(m.header.frame_id, "")
        self.assertTrue(math.isnan(m.temperature))

    def test_module_diagnostics(self):
        arr = self.diag.wait_for(lambda a: module_status(a, "temperature module 1") is not None and
                                 "abnormal" in module_status(a, "temperature module 1").message)
        s = module_status(arr, "temperature module 1")
        self.assertIsNotNone(s)
        self.assertIn("FBs-2TC", s.name)
        self.assertEqual(s.level, DiagnosticStatus.WARN)
        self.assertIn("broken", s.message)

    def test_set_pid_loop(self):
        # The program writes its settings on the first scan; wait until they are there.
        pid = Latest(NS + "registers/oven_pid", RegisterBlock, timeout=TIMEOUT)  # R100 R120 R130 R140
        self.assertEqual(pid.wait_for(lambda m: m.values[0] == 2000).values[0], 2000)
        r = self.set_loop("oven", 180.5, 90, -1, 0)
        self.assertTrue(r.success, r.message)
        self.assertEqual(list(self.read("R100", 1).values), [1805])
        self.assertEqual(list(self.read("R120", 1).values), [90])
        self.assertEqual(list(self.read("R130", 1).values), [40])  # unchanged
        self.assertEqual(list(self.read("R140", 1).values), [0])
        r = self.set_loop("oven", float("nan"), 0, -1, -1)
        self.assertFalse(r.success)
        self.assertIn("kc", r.message)
        r = self.set_loop("nope", 100.0, -1, -1, -1)
        self.assertFalse(r.success)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "temperature_test", TemperatureTest)
