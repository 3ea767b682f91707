#!/usr/bin/python3
"""rostest: modbus_bridge against plc_node's Modbus/TCP slave publishes what the
PLC holds, and its write service changes the PLC's memory."""
import os
import sys
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from std_msgs.msg import Float32, Float64, Int16
from std_srvs.srv import Trigger

from plc_cell.msg import RegisterBlock
from plc_cell.srv import ReadMemory, WriteMemory, WritePoint

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import Latest  # noqa: E402
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reliability"))
from bridge_faults import misbehaving_device_keeps_reporting  # noqa: E402

TIMEOUT = 20.0




class ModbusBridgeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("modbus_bridge_test")
        for s in ("/plc_node/read", "/plc_node/write", "/modbus_bridge/write", "/modbus_bridge/recover"):
            rospy.wait_for_service(s, timeout=30)
        cls.plc_read = rospy.ServiceProxy("/plc_node/read", ReadMemory)
        cls.plc_write = rospy.ServiceProxy("/plc_node/write", WriteMemory)
        cls.write = rospy.ServiceProxy("/modbus_bridge/write", WritePoint)
        cls.recover = rospy.ServiceProxy("/modbus_bridge/recover", Trigger)

    def plc(self, address):
        # The bridge's write service answers after the slave did: no waiting needed.
        return list(self.plc_read(address, 1).values)

    def test_publishes_what_the_plc_holds(self):
        a = Latest("/modbus_bridge/plc/a", Int16, timeout=TIMEOUT)
        level = Latest("/modbus_bridge/plc/level", Float32, timeout=TIMEOUT)
        temp = Latest("/modbus_bridge/plc/temp", Float64, timeout=TIMEOUT)
        self.assertTrue(self.plc_write("R11", [1234]).success)
        # DR100 = 0x40490FDB (float 3.1415927): word-swapped, low word at D100.
        self.assertTrue(self.plc_write("D100", [0x40490FDB & 0xFFFF, 0x4049]).success)
        self.assertTrue(self.plc_write("D102", [215]).success)
        m = a.wait_for(lambda m: m.data == 1234)
        self.assertEqual(m.data, 1234)
        m = level.wait_for(lambda m: abs(m.data - 3.1415927) < 1e-6)
        self.assertAlmostEqual(m.data, 3.1415927, places=6)
        m = temp.wait_for(lambda m: abs(m.data - 21.5) < 1e-9)
        self.assertAlmostEqual(m.data, 21.5)

    def test_write_service_changes_the_plc(self):
        total = Latest("/modbus_bridge/plc/sum", Int16, timeout=TIMEOUT)
        r = self.write("plc/a", 40)
        self.assertTrue(r.success, r.message)
        r = self.write("b", -2)
        self.assertTrue(r.success, r.message)
        self.assertEqual(self.plc("R11"), [40])
        self.assertEqual(self.plc("R12"), [0xFFFE])
        # The program computes R10 = R11 + R12; the bridge publishes it.
        m = total.wait_for(lambda m: m.data == 38)
        self.assertEqual(m.data, 38)
        r = self.write("temp", 30.2)
        self.assertTrue(r.success, r.message)
        self.assertEqual(self.plc("D102"), [302])
        r = self.write("m10", 1)
        self.assertTrue(r.success, r.message)
        self.assertEqual(self.plc("M10"), [1])
        r = self.write("nope", 1)
        self.assertFalse(r.success)
        r = self.write("a", 40000)  # does not fit int16
        self.assertFalse(r.success)

    def test_blocks_diagnostics_and_recover(self):
        blocks = Latest("/modbus_bridge/plc/blocks", RegisterBlock, timeout=TIMEOUT)
        m = blocks.wait_for(lambda m: m.name == "fast" and m.address == "holding_register:10")
        self.assertIsNotNone(m)
        self.assertEqual(len(m.values), 3)
        self.assertTrue(self.recover().success)
        diags = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)

        def plc_ok(msg):
            return any(s.name.endswith("plc") and s.level == 0 for s in msg.status)
        m = diags.wait_for(plc_ok)
        self.assertTrue(m is not None and plc_ok(m))

    def test_misbehaving_device_keeps_diagnostics_and_recovers(self):
        # modbus_bridge_flaky polls plc_node through flaky_device.py.
        diags = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)
        blocks = Latest("/modbus_bridge_flaky/flaky/blocks", RegisterBlock, timeout=TIMEOUT)
        misbehaving_device_keeps_reporting(self, diags, "modbus_bridge_flaky", "/flaky_modbus/", blocks)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "modbus_bridge_test", ModbusBridgeTest)
