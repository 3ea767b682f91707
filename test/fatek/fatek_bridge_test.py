#!/usr/bin/python3
"""rostest: fatek_bridge publishes what the soft PLC holds, and its services change it."""
import os
import sys
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from std_msgs.msg import Bool

from plc_cell.msg import IoState, RegisterBlock, Signal

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import Latest  # noqa: E402
from bridge_services import connect_services, write_ok  # noqa: E402
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reliability"))
from bridge_faults import misbehaving_device_keeps_reporting  # noqa: E402

NS = "/fatek_bridge/"
TIMEOUT = 20.0




class FatekBridgeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("fatek_bridge_test", anonymous=True)
        connect_services(cls, NS)
        cls.io = Latest(NS + "io", IoState, timeout=TIMEOUT)
        cls.regs = Latest(NS + "registers/regs", RegisterBlock, timeout=TIMEOUT)
        cls.motor = Latest(NS + "signals/motor", Bool, timeout=TIMEOUT)
        cls.diag = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)

    def write_ok(self, address, values):
        return write_ok(self.write, self.io, address, values, TIMEOUT)

    def test_1_registers_follow_the_plc(self):
        m = self.regs.wait_for(lambda m: len(m.values) == 5)
        self.assertIsNotNone(m)
        self.assertEqual(m.name, "regs")
        self.assertEqual(m.address, "R10:3,D0,R20")
        r = self.write_ok("R11", [5, 7])  # R11 = 5, R12 = 7 -> the program computes R10 = 12
        self.assertTrue(r.success, r.message)
        m = self.regs.wait_for(lambda m: list(m.values[:3]) == [12, 5, 7])
        self.assertEqual(list(m.values[:3]), [12, 5, 7])
        r = self.write_ok("R20", [4242])  # the program copies R20 to D0
        self.assertTrue(r.success, r.message)
        m = self.regs.wait_for(lambda m: m.values[3] == 4242 and m.values[4] == 4242)
        self.assertEqual(list(m.values[3:]), [4242, 4242])

    def test_2_io_image_and_signals(self):
        r = self.write_ok("start", [1])  # X0 by its signal name; the program drives Y0
        self.assertTrue(r.success, r.message)
        m = self.io.wait_for(lambda m: m.x[0] and m.y[0])
        self.assertTrue(m.x[0])
        self.assertTrue(m.y[0])
        self.assertEqual(len(m.x), 256)
        self.assertTrue(self.motor.wait_for(lambda m: m.data).data)
        r = self.write_ok("X0", [0])
        self.assertTrue(r.success, r.message)
        self.assertFalse(self.motor.wait_for(lambda m: not m.data).data)

    def test_3_run_stop(self):
        self.assertTrue(self.io.wait_for(lambda m: m.run).run)
        r = self.set_run(False)
        self.assertTrue(r.success, r.message)
        self.assertFalse(self.io.wait_for(lambda m: not m.run).run)
        r = self.set_run(True)
        self.assertTrue(r.success, r.message)
        self.assertTrue(self.io.wait_for(lambda m: m.run).run)

    def test_4_bad_write_is_reported(self):
        r = self.write("R9000", [1])
        self.assertFalse(r.success)
        self.assertIn("R9000", r.message)

    def test_5_diagnostics_and_recover(self):
        def connected(m):
            return any(s.name.endswith("link") and s.level == 0 for s in m.status)
        self.assertTrue(connected(self.diag.wait_for(connected)))
        self.assertTrue(self.recover().success)
        stamp = rospy.Time.now()
        m = self.regs.wait_for(lambda m: m.header.stamp > stamp)
        self.assertGreater(m.header.stamp, stamp)

    def test_7_read(self):
        r = self.write_ok("R11", [5, 7])
        self.assertTrue(r.success, r.message)
        r = self.read("R11", 2)
        self.assertTrue(r.success, r.message)
        self.assertEqual(list(r.values), [5, 7])
        r = self.read("R11", 0)  # 0 reads one element
        self.assertEqual(list(r.values), [5])
        r = self.read("start", 0)  # a signal name, as ~write takes it
        self.assertTrue(r.success, r.message)
        self.assertEqual(len(r.values), 1)
        r = self.read("R9000", 1)
        self.assertFalse(r.success)
        self.assertIn("R9000", r.message)
        # ~write takes what plc_node's takes: two's complement within the element's range,
        # and a value beyond it is refused with the range, before anything is written.
        self.assertTrue(self.write_ok("R40", [-2]).success)
        self.assertEqual(list(self.read("R40", 1).values), [65534])
        r = self.write("R11", [1, 70000])
        self.assertFalse(r.success)
        self.assertIn("-32768..65535", r.message)
        self.assertEqual(list(self.read("R11", 1).values), [5])

    def test_8_force_release_and_stamped_signals(self):
        stamped = Latest(NS + "signals_stamped/motor", Signal, timeout=TIMEOUT)
        self.assertTrue(self.write_ok("X0", [0]).success)
        self.assertFalse(self.motor.wait_for(lambda m: not m.data).data)
        before = rospy.Time.now()
        r = self.force("start", True)  # X0, locked ON: the program drives Y0
        self.assertTrue(r.success, r.message)
        self.assertEqual(r.message, "X0 forced ON")
        m = stamped.wait_for(lambda m: m.data)
        self.assertTrue(m.data)
        self.assertGreaterEqual(m.header.stamp, before)
        self.assertEqual(m.header.frame_id, "")  # no ~frame_id given
        self.assertEqual(self.io.wait_for(lambda m: m.y[0]).header.frame_id, "")
        # Locked: a write does not move it.
        self.assertTrue(self.write("X0", [0]).success)
        self.assertEqual(list(self.read("X0", 1).values), [1])
        self.assertFalse(self.force("R0", True).success)
        r = self.release("")
        self.assertTrue(r.success, r.message)
        self.assertEqual(list(r.released), ["X0"])
        r = self.release("X0")
        self.assertTrue(r.success, r.message)
        self.assertEqual((list(r.released), r.message), ([], "nothing was forced"))
        self.assertTrue(self.write("X0", [0]).success)  # free again
        self.assertFalse(stamped.wait_for(lambda m: not m.data).data)

    def test_6_misbehaving_device_keeps_diagnostics_and_recovers(self):
        # fatek_bridge_flaky polls a second soft PLC over TCP through flaky_device.py.
        io = Latest("/fatek_bridge_flaky/io", IoState, timeout=TIMEOUT)
        misbehaving_device_keeps_reporting(self, self.diag, "fatek_bridge_flaky", "/flaky_fatek/", io)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "fatek_bridge_test", FatekBridgeTest)
