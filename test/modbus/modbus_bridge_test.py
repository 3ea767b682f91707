#!/usr/bin/python3
"""rostest: modbus_bridge against plc_node's Modbus/TCP slave publishes what the
PLC holds, and its write service changes the PLC's memory."""
import os
import pty
import subprocess
import sys
import time
import unittest

import rospy
import rosservice
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
from tool_path import find_tool  # noqa: E402

PLC_NODE = find_tool("plc_node")  # not rosrun: its search loops in the workspace inside the package

TIMEOUT = 20.0




class ModbusBridgeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("modbus_bridge_test")
        for s in ("/plc_node/read", "/plc_node/write", "/modbus_bridge/write_point", "/modbus_bridge/recover"):
            rospy.wait_for_service(s, timeout=30)
        cls.plc_read = rospy.ServiceProxy("/plc_node/read", ReadMemory)
        cls.plc_write = rospy.ServiceProxy("/plc_node/write", WriteMemory)
        cls.write = rospy.ServiceProxy("/modbus_bridge/write_point", WritePoint)
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

    def test_a_service_name_means_one_type(self):
        # ~write is WriteMemory (raw elements at an address) on every node; the bridge's
        # point write, an engineering value by point name, has a name of its own.
        self.assertEqual(rosservice.get_service_type("/plc_node/write"), "plc_cell/WriteMemory")
        self.assertEqual(rosservice.get_service_type("/modbus_bridge/write_point"), "plc_cell/WritePoint")
        self.assertIsNone(rosservice.get_service_type("/modbus_bridge/write"))

    def test_gateway_wait_is_in_seconds(self):
        cell = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "ros", "test_cell.yaml")
        master, slave = pty.openpty()  # the gateway's RTU line: a tty nobody answers on
        diags = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)

        def gateway_status(msg):
            return msg is not None and any(
                "plc_node_gateway" in s.name and any("wait 250 ms" in kv.key for kv in s.values) for s in msg.status)
        try:
            node = subprocess.Popen(
                [PLC_NODE, "__name:=plc_node_gateway", "_cell:=" + cell,
                 "_modbus_tcp:=127.0.0.1:15023", "_modbus_gateway:=" + os.ttyname(slave),
                 "_modbus_gateway_wait:=0.25"],
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            try:
                # The server's description on /diagnostics gives the wait it runs with.
                self.assertTrue(gateway_status(diags.wait_for(gateway_status)))
            finally:
                node.terminate()
                node.wait(timeout=TIMEOUT)
        finally:
            os.close(master)
            os.close(slave)
        # A value in milliseconds, as the old ~modbus_gateway_wait_ms took, is refused.
        bad = subprocess.run(
            [PLC_NODE, "__name:=plc_node_bad_wait", "_cell:=" + cell,
             "_modbus_gateway_wait:=150"],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=TIMEOUT)
        self.assertNotEqual(bad.returncode, 0)
        self.assertIn("~modbus_gateway_wait 150", bad.stdout)
        self.assertIn("out of range [0.001, 60]", bad.stdout)
        old = subprocess.run(
            [PLC_NODE, "__name:=plc_node_old_wait", "_cell:=" + cell,
             "_modbus_gateway_wait_ms:=150"],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=TIMEOUT)
        self.assertNotEqual(old.returncode, 0)
        self.assertIn("give ~modbus_gateway_wait in seconds", old.stdout)

    def test_blocks_diagnostics_and_recover(self):
        blocks = Latest("/modbus_bridge/plc/blocks", RegisterBlock, timeout=TIMEOUT)
        m = blocks.wait_for(lambda m: m.name == "fast" and m.address == "holding_register:10")
        self.assertIsNotNone(m)
        self.assertEqual(len(m.values), 3)
        self.assertEqual(m.header.frame_id, "")  # no ~frame_id: a device name is no frame
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
