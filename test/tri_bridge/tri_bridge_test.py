#!/usr/bin/python3
"""rostest: tri_bridge publishes what the soft PLC (plc_cell run --tri-tcp) holds under
plc_node's topic names, and its services change it."""
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

NS = "/tri_bridge/"
TIMEOUT = 20.0


class TriBridgeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("tri_bridge_test", anonymous=True)
        connect_services(cls, NS)
        cls.io = Latest(NS + "io", IoState, timeout=TIMEOUT)
        cls.dm = Latest(NS + "registers/dm", RegisterBlock, timeout=TIMEOUT)
        cls.motor = Latest(NS + "signals/motor", Bool, timeout=TIMEOUT)
        cls.diag = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)

    def write_ok(self, address, values):
        return write_ok(self.write, self.io, address, values, TIMEOUT)

    def test_1_registers_follow_the_plc(self):
        m = self.dm.wait_for(lambda m: len(m.values) == 7)
        self.assertIsNotNone(m)
        self.assertEqual(m.name, "dm")
        self.assertEqual(m.address, "DM[1]:5,A,TIMERPV[1]")
        r = self.write_ok("DM[1]", [4242])  # the program copies DM[1] to DM[2]
        self.assertTrue(r.success, r.message)
        m = self.dm.wait_for(lambda m: list(m.values[:2]) == [4242, 4242])
        self.assertEqual(list(m.values[:2]), [4242, 4242])
        r = self.write_ok("D2", [5, 7])  # DM[3], DM[4] by their plc_node names: DM[5] = 12
        self.assertTrue(r.success, r.message)
        m = self.dm.wait_for(lambda m: list(m.values[2:5]) == [5, 7, 12])
        self.assertEqual(list(m.values[2:5]), [5, 7, 12])
        r = self.write_ok("A", [123456])
        self.assertTrue(r.success, r.message)
        m = self.dm.wait_for(lambda m: m.values[5] == 123456)
        self.assertEqual(m.values[5], 123456)

    def test_2_io_image_and_signals(self):
        r = self.write_ok("start", [1])  # X0 (INPUT 1) by its signal name; the program drives Y0
        self.assertTrue(r.success, r.message)
        m = self.io.wait_for(lambda m: m.x[0] and m.y[0])
        self.assertTrue(m.x[0])
        self.assertTrue(m.y[0])
        self.assertEqual(len(m.x), 256)
        self.assertEqual(len(m.y), 256)
        self.assertTrue(self.motor.wait_for(lambda m: m.data).data)
        r = self.write_ok("X0", [0])
        self.assertTrue(r.success, r.message)
        self.assertFalse(self.motor.wait_for(lambda m: not m.data).data)

    def test_3_read(self):
        self.assertTrue(self.write_ok("DM[3]", [9, 8]).success)
        r = self.read("DM[3]", 2)
        self.assertTrue(r.success, r.message)
        self.assertEqual(list(r.values), [9, 8])
        r = self.read("D4000", 1)  # beyond DM[4000]
        self.assertFalse(r.success)
        self.assertIn("not on a TRi", r.message)
        r = self.write("R3761", [1])  # half of A
        self.assertFalse(r.success)
        self.assertIn("32-bit", r.message)
        # A value that does not fit names the point as it was written, and its element.
        r = self.write("DM[3]", [70000])
        self.assertFalse(r.success)
        self.assertEqual(r.message, "DM[3] -> D2: value 70000 out of range -32768..65535")
        r = self.write("DM[3]", [1, -40000])
        self.assertFalse(r.success)
        self.assertEqual(r.message, "DM[3] + 1 -> D3: value -40000 out of range -32768..65535")
        self.assertEqual(list(self.read("DM[3]", 2).values), [9, 8])  # a refused write changes nothing

    def test_4_force_release_and_stamped_signals(self):
        stamped = Latest(NS + "signals_stamped/motor", Signal, timeout=TIMEOUT)
        self.assertTrue(self.write_ok("X0", [0]).success)
        self.assertFalse(self.motor.wait_for(lambda m: not m.data).data)
        r = self.force("start", True)  # X0 held ON: the program drives Y0
        self.assertTrue(r.success, r.message)
        self.assertEqual(r.message, "X0 forced ON")
        self.assertTrue(stamped.wait_for(lambda m: m.data).data)
        self.assertFalse(self.force("DM[1]", True).success)
        r = self.release("")
        self.assertTrue(r.success, r.message)
        self.assertEqual(list(r.released), ["X0"])
        r = self.release("X0")
        self.assertEqual((list(r.released), r.message), ([], "nothing was forced"))
        self.assertTrue(self.write("X0", [0]).success)  # no longer held
        self.assertFalse(stamped.wait_for(lambda m: not m.data).data)

    def test_5_run_stop(self):
        r = self.set_run(False)  # C2 halt
        self.assertTrue(r.success, r.message)
        self.assertFalse(self.io.wait_for(lambda m: not m.run).run)
        r = self.set_run(True)  # C3 resume
        self.assertTrue(r.success, r.message)
        self.assertTrue(self.io.wait_for(lambda m: m.run).run)

    def test_6_diagnostics_and_recover(self):
        def connected(m):
            return any(s.name.endswith("link") and s.level == 0 for s in m.status)
        self.assertTrue(connected(self.diag.wait_for(connected)))
        self.assertTrue(self.recover().success)
        stamp = rospy.Time.now()
        m = self.dm.wait_for(lambda m: m.header.stamp > stamp)
        self.assertGreater(m.header.stamp, stamp)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "tri_bridge_test", TriBridgeTest)
