#!/usr/bin/python3
"""Cells as nodelets of one manager: each its own cell, topics, services and /diagnostics."""
import os
import sys
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from std_msgs.msg import Bool
from plc_cell.srv import ReadMemory

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import Latest  # noqa: E402

CELLS = 3
TIMEOUT = 20.0


def ns(i):
    return "/cell_%d/plc_node/" % i


class NodeletsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("nodelets_test", anonymous=True)
        for i in range(CELLS):
            rospy.wait_for_service(ns(i) + "read", timeout=60)

    def test_each_cell_has_its_own_memory_and_topics(self):
        """An input on cell 1's topic drives cell 1's output, and no other cell's."""
        motors = [Latest(ns(i) + "signals/motor", Bool, timeout=TIMEOUT) for i in range(CELLS)]
        for m in motors:
            self.assertFalse(m.wait_for(lambda msg: True).data)
        start = rospy.Publisher(ns(1) + "inputs/start", Bool, queue_size=1, latch=True)
        start.publish(Bool(True))
        self.assertTrue(motors[1].wait_for(lambda msg: msg.data).data)
        for i in (0, 2):
            read = rospy.ServiceProxy(ns(i) + "read", ReadMemory)
            self.assertEqual(list(read("Y0", 1).values), [0], "cell %d followed cell 1's input" % i)
        self.assertEqual(list(rospy.ServiceProxy(ns(1) + "read", ReadMemory)("Y0", 1).values), [1])

    def test_each_cell_reports_its_own_scan(self):
        seen = set()
        diag = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)

        def all_cells(msg):
            for st in msg.status:
                if st.name.endswith("plc_node: scan"):
                    seen.add(st.name)
            return len(seen) >= CELLS

        diag.wait_for(all_cells)
        self.assertEqual(sorted(seen), ["cell_%d/plc_node: scan" % i for i in range(CELLS)])


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "nodelets_test", NodeletsTest)
