#!/usr/bin/python3
"""rostest: plc_node's ~fatek_serial server, seen through fatek_bridge on the other pty end."""
import time
import unittest

import rospy
import rostest

from plc_cell.msg import RegisterBlock
from plc_cell.srv import ReadMemory, WriteMemory

from fatek_bridge_test import Latest

TIMEOUT = 20.0


class PlcNodeFatekTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("plc_node_fatek_test", anonymous=True)
        for s in ["/plc_node/write", "/plc_node/read", "/fatek_bridge/write"]:
            rospy.wait_for_service(s, timeout=30)
        cls.node_write = rospy.ServiceProxy("/plc_node/write", WriteMemory)
        cls.node_read = rospy.ServiceProxy("/plc_node/read", ReadMemory)
        cls.bridge_write = rospy.ServiceProxy("/fatek_bridge/write", WriteMemory)
        cls.regs = Latest("/fatek_bridge/registers/regs", RegisterBlock)

    def test_values_cross_the_fatek_link_both_ways(self):
        # plc_node's program computes R10 = R11 + R12; the bridge reads it over FATEK.
        self.assertTrue(self.node_write("R11", [30, 12]).success)
        m = self.regs.wait_for(lambda m: list(m.values[:3]) == [42, 30, 12])
        self.assertIsNotNone(m)
        self.assertEqual(list(m.values[:3]), [42, 30, 12])
        # A write through the bridge lands in plc_node's memory.
        deadline = time.monotonic() + TIMEOUT
        r = self.bridge_write("R20", [777])
        while not r.success and time.monotonic() < deadline:
            self.regs.wait_for(lambda m: True, timeout=1.0)
            r = self.bridge_write("R20", [777])
        self.assertTrue(r.success, r.message)
        self.assertEqual(list(self.node_read("R20", 1).values), [777])


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "plc_node_fatek_test", PlcNodeFatekTest)
