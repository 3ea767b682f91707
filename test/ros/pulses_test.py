#!/usr/bin/python3
"""rostest: ~pulses/<input> (width, period, frequency of counter inputs) beside the counts."""
import os
import sys
import time
import unittest

import rospy
import rostest
from std_msgs.msg import Float64

from plc_cell.msg import Counter, PulseMeasurement

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import Latest  # noqa: E402

NS = "/plc_node/"
TIMEOUT = 15.0


class PulsesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("pulses_test", anonymous=True)
        cls.x0 = Latest(NS + "pulses/X0", PulseMeasurement, timeout=TIMEOUT)
        cls.x4 = Latest(NS + "pulses/X4", PulseMeasurement, timeout=TIMEOUT)
        cls.spindle = Latest(NS + "counters/spindle", Counter, timeout=TIMEOUT)
        cls.rate = rospy.Publisher(NS + "sources/gen/rate", Float64, queue_size=1, latch=True)

    def set_rate(self, hz):
        deadline = time.monotonic() + TIMEOUT
        while self.rate.get_num_connections() == 0 and time.monotonic() < deadline:
            rospy.rostime.wallsleep(0.05)  # waiting for plc_node's subscription, not for the cell
        self.assertGreater(self.rate.get_num_connections(), 0)
        self.rate.publish(Float64(hz))

    def test_1_a_1khz_generator_reads_1000us_500us_1000hz(self):
        msg = self.x0.wait_for(lambda m: m.period > 0)
        self.assertIsNotNone(msg)
        self.assertEqual(msg.name, "X0")
        self.assertEqual(msg.input, 0)
        self.assertEqual(msg.counter, "spindle")
        self.assertEqual(msg.unit, "us")
        self.assertEqual(msg.period, 1000.0)
        self.assertEqual(msg.width, 500.0)
        self.assertEqual(msg.frequency, 1000.0)
        self.assertEqual(msg.header.frame_id, "spindle_sensor")
        self.assertGreater(msg.header.stamp.to_nsec(), 0)

    def test_2_a_pulse_train_reads_its_duty(self):
        msg = self.x4.wait_for(lambda m: m.period > 0)
        self.assertIsNotNone(msg)
        self.assertEqual((msg.name, msg.input, msg.counter), ("X4", 4, "sensor"))
        self.assertEqual(msg.period, 4000.0)
        self.assertEqual(msg.width, 1000.0)
        self.assertEqual(msg.frequency, 250.0)

    def test_3_counted_at_the_same_time(self):
        first = self.spindle.wait_for(lambda m: m.count > 0)
        self.assertIsNotNone(first)
        later = self.spindle.wait_for(lambda m: m.count > first.count + 100)
        self.assertGreater(later.count, first.count + 100)
        self.assertEqual(self.x0.wait_for(lambda m: m.period > 0).period, 1000.0)

    def test_4_stopped_reads_zero_and_a_new_rate_is_measured(self):
        self.x0.wait_for(lambda m: m.period > 0)
        self.set_rate(0.0)
        msg = self.x0.wait_for(lambda m: m.period == 0.0)
        self.assertEqual((msg.width, msg.period, msg.frequency), (0.0, 0.0, 0.0))
        stopped = self.spindle.wait_for(lambda m: m.frequency == 0.0)
        count = stopped.count
        self.set_rate(2000.0)
        msg = self.x0.wait_for(lambda m: m.period > 0)
        self.assertEqual((msg.width, msg.period, msg.frequency), (250.0, 500.0, 2000.0))
        self.assertGreater(self.spindle.wait_for(lambda m: m.count > count).count, count)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "pulses_test", PulsesTest)
