#!/usr/bin/python3
"""rostest: two plc_nodes in namespaces do not see each other's memory, inputs or outputs."""
import os
import signal
import sys
import unittest
import xmlrpc.client

import rosgraph

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from std_msgs.msg import Bool

from plc_cell.srv import ReadMemory, WriteMemory

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import Latest  # noqa: E402

TIMEOUT = 15.0


def status_named(arr, part):
    for s in arr.status:
        if part in s.name:
            return s
    return None


class TwoCellsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("two_cells_test", anonymous=True)
        cls.srv = {}
        for c in ["cell_a", "cell_b"]:
            ns = "/%s/plc_node/" % c
            rospy.wait_for_service(ns + "write", timeout=30)
            cls.srv[c] = (rospy.ServiceProxy(ns + "read", ReadMemory), rospy.ServiceProxy(ns + "write", WriteMemory))
        cls.motor = {c: Latest("/%s/plc_node/signals/motor" % c, Bool, timeout=TIMEOUT) for c in ["cell_a", "cell_b"]}
        cls.start = {c: rospy.Publisher("/%s/plc_node/inputs/start" % c, Bool, queue_size=1, latch=True)
                     for c in ["cell_a", "cell_b"]}
        cls.diag = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)

    def read(self, cell, addr):
        r = self.srv[cell][0](addr, 1)
        self.assertTrue(r.success, r.message)
        return r.values[0]

    def test_memory_is_per_cell(self):
        self.assertTrue(self.srv["cell_a"][1]("R11", [20]).success)
        self.assertTrue(self.srv["cell_b"][1]("R11", [1]).success)
        self.assertEqual(self.read("cell_a", "R11"), 20)
        self.assertEqual(self.read("cell_b", "R11"), 1)

    def test_inputs_and_outputs_are_per_cell(self):
        self.start["cell_b"].publish(Bool(False))
        self.start["cell_a"].publish(Bool(True))
        m = self.motor["cell_a"].wait_for(lambda m: m.data)
        self.assertTrue(m is not None and m.data)
        b = self.motor["cell_b"].wait_for(lambda m: m is not None)
        self.assertFalse(b.data)
        self.start["cell_a"].publish(Bool(False))
        m = self.motor["cell_a"].wait_for(lambda m: not m.data)
        self.assertFalse(m.data)

    def test_persistence_of_cell_a_is_on_diagnostics(self):
        self.assertTrue(self.srv["cell_a"][1]("D7", [1234]).success)
        arr = self.diag.wait_for(lambda a: status_named(a, "cell_a") is not None and
                                 status_named(a, "persistence") is not None)
        s = status_named(arr, "persistence")
        self.assertIsNotNone(s)
        self.assertEqual(s.level, 0, s.message)
        self.assertIn("cell_a", s.name)
        keys = dict((kv.key, kv.value) for kv in s.values)
        self.assertTrue(keys["file"].endswith("two_cells_a_store.bin"))

    def test_each_cell_has_its_own_hardware_id(self):
        # Both cells run test_cell.yaml: the same cell name, so the node tells them apart.
        ids = {}
        for c in ["cell_a", "cell_b"]:
            arr = self.diag.wait_for(lambda a: any(c + "/plc_node" in s.name for s in a.status))
            ids[c] = [s.hardware_id for s in arr.status if c + "/plc_node" in s.name][0]
        self.assertNotEqual(ids["cell_a"], ids["cell_b"])
        self.assertIn("test_cell", ids["cell_a"])
        self.assertIn("/cell_a/plc_node", ids["cell_a"])

    def test_z_a_crashed_cell_restarts_alone(self):
        """kill -9 of cell_a: cell_b keeps scanning, cell_a respawns with its retentive D7, and
        /diagnostics shows the new process (pid, uptime)."""
        self.assertTrue(self.srv["cell_a"][1]("D7", [4321]).success)  # acknowledged, so on disk

        def scan_status(arr, cell):
            # diagnostic_updater announces each task of a starting node once, as "Node
            # starting up" with no values: that is not yet the cell's scan report.
            for st in arr.status:
                if cell in st.name and st.name.endswith("scan") and any(kv.key == "pid" for kv in st.values):
                    return dict((kv.key, kv.value) for kv in st.values)
            return None
        # Each node publishes its own DiagnosticArray: look for each cell's in turn.
        before = self.diag.wait_for(lambda a: scan_status(a, "cell_a") is not None)
        old_pid = int(scan_status(before, "cell_a")["pid"])
        b_before = self.diag.wait_for(lambda a: scan_status(a, "cell_b") is not None)
        b_pid = scan_status(b_before, "cell_b")["pid"]
        uri = rosgraph.Master("/two_cells_test").lookupNode("/cell_a/plc_node")
        code, _, pid = xmlrpc.client.ServerProxy(uri).getPid("/two_cells_test")
        self.assertEqual((code, pid), (1, old_pid))
        os.kill(pid, signal.SIGKILL)

        # cell_b is untouched: its program still answers its input.
        self.start["cell_b"].publish(Bool(True))
        self.assertTrue(self.motor["cell_b"].wait_for(lambda m: m.data).data)
        self.start["cell_b"].publish(Bool(False))
        self.assertFalse(self.motor["cell_b"].wait_for(lambda m: not m.data).data)

        # cell_a comes back by itself, as a new process, with its acknowledged write.
        after = self.diag.wait_for(lambda a: scan_status(a, "cell_a") is not None and
                                   int(scan_status(a, "cell_a")["pid"]) != old_pid, timeout=30)
        st = scan_status(after, "cell_a")
        self.assertNotEqual(int(st["pid"]), old_pid, "cell_a did not come back")
        self.assertLess(float(st["uptime (s)"]), 30.0)
        rospy.wait_for_service("/cell_a/plc_node/read", timeout=30)
        read_a = rospy.ServiceProxy("/cell_a/plc_node/read", ReadMemory)
        self.assertEqual(list(read_a("D7", 1).values), [4321])
        b = scan_status(self.diag.wait_for(lambda a: scan_status(a, "cell_b") is not None), "cell_b")
        self.assertEqual(b["pid"], b_pid, "cell_b was restarted too")


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "two_cells_test", TwoCellsTest)
