#!/usr/bin/python3
"""rostest: the simulated conveyor encoder on the counters topics; preset and clear."""
import os
import sys
import unittest

import rospy
import rostest
from std_srvs.srv import Trigger

from diagnostic_msgs.msg import DiagnosticArray
from plc_cell.msg import Counter, CounterArray
from plc_cell.srv import PresetCounter

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import Latest  # noqa: E402

NS = "/plc_node/"
TIMEOUT = 15.0




class CountersTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("counters_test", anonymous=True)
        rospy.wait_for_service(NS + "counters/conveyor/preset", timeout=30)
        cls.preset = rospy.ServiceProxy(NS + "counters/conveyor/preset", PresetCounter)
        cls.clear = rospy.ServiceProxy(NS + "counters/conveyor/clear", Trigger)
        cls.all = Latest(NS + "counters", CounterArray, timeout=TIMEOUT)
        cls.one = Latest(NS + "counters/conveyor", Counter, timeout=TIMEOUT)

    def test_1_encoder_count_stops_at_the_preset(self):
        # 1 kHz x4 = 4000 counts/s; the HSC0I routine stops the motor at CV = PV = 4000.
        msg = self.all.wait_for(lambda m: len(m.counters) == 1 and m.counters[0].count >= 4000)
        self.assertIsNotNone(msg)
        self.assertEqual(msg.counters[0].name, "conveyor")
        self.assertEqual(msg.counters[0].number, 0)
        self.assertEqual(msg.counters[0].count, 4000)
        self.assertEqual(msg.header.frame_id, "belt_encoder")  # ~frame_id
        # One instant, one header (seq is the connection's own).
        self.assertEqual((msg.counters[0].header.stamp, msg.counters[0].header.frame_id),
                         (msg.header.stamp, msg.header.frame_id))
        one = self.one.wait_for(lambda m: m.count == 4000)
        self.assertEqual(one.count, 4000)
        # Published alone, a Counter says when and where it was read.
        self.assertEqual(one.header.frame_id, "belt_encoder")
        self.assertGreater(one.header.stamp.to_nsec(), 0)
        # Stopped: the frequency falls to 0 once the window has passed.
        one = self.one.wait_for(lambda m: m.frequency == 0.0)
        self.assertEqual(one.frequency, 0.0)
        self.assertEqual(one.count, 4000)

    def test_2_preset_and_clear(self):
        self.one.wait_for(lambda m: m.count == 4000)
        self.assertTrue(self.preset(123).success)
        self.assertEqual(self.one.wait_for(lambda m: m.count == 123).count, 123)
        self.assertTrue(self.clear().success)
        self.assertEqual(self.one.wait_for(lambda m: m.count == 0).count, 0)

    def test_3_the_counters_extension_reports_on_diagnostics(self):
        # Each cell extension's status is a /diagnostics entry: the counters name theirs.
        diag = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)
        # Not diagnostic_updater's "Node starting up" announcement, which has no values.
        def counters(m):
            return [s for s in m.status if s.name.endswith(": counters") and s.values]
        msg = diag.wait_for(lambda m: bool(counters(m)))
        self.assertIsNotNone(msg)
        st = counters(msg)[0]
        self.assertEqual(st.level, 0, st.message)
        self.assertEqual(st.message, "1 counter configured")
        values = dict((kv.key, kv.value) for kv in st.values)
        self.assertEqual(list(values), ["conveyor"])
        self.assertGreaterEqual(int(values["conveyor"]), 0)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "counters_test", CountersTest)
