#!/usr/bin/python3
"""rostest: kill -9 of plc_node loses no acknowledged write to a retentive range."""
import os
import signal
import struct
import subprocess
import tempfile
import unittest

import rospkg
import rospy
import rostest

from plc_cell.srv import ReadMemory, WriteMemory

NODE = "restart_plc"


class NodeRestartTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("node_restart_test", anonymous=True)
        pkg = rospkg.RosPack().get_path("plc_cell")
        cls.cell = os.path.join(pkg, "test", "ros", "test_cell.yaml")
        cls.store = os.path.join(tempfile.mkdtemp(prefix="plc_cell_restart_"), "store.bin")

    @staticmethod
    def node_binary():
        # The devel/install space's lib/plc_cell; rosrun would search the source tree too.
        for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(":"):
            path = os.path.join(prefix, "lib", "plc_cell", "plc_node")
            if prefix and os.access(path, os.X_OK):
                return path
        raise RuntimeError("plc_node not found under CMAKE_PREFIX_PATH")

    def start(self):
        proc = subprocess.Popen(
            [self.node_binary(), "__name:=" + NODE, "_cell:=" + self.cell,
             "_persist_file:=" + self.store, "_persist_interval:=0.1"],
            stdin=subprocess.DEVNULL)
        rospy.wait_for_service("/%s/write" % NODE, timeout=30)
        return proc

    @staticmethod
    def newest_slot(path):
        """(sequence, payload) of the newest slot whose header is readable: [magic "PSR1",
        sequence u64, length u32, CRC u32, payload], two slots of equal size."""
        with open(path, "rb") as f:
            data = f.read()
        best = (0, b"")
        for off in (0, len(data) // 2):
            magic, seq, n, _ = struct.unpack_from("<IQII", data, off)
            if magic == 0x31525350 and seq > best[0]:
                best = (seq, data[off + 20:off + 20 + n])
        return best

    def test_sigterm_and_sigint_stop_cleanly_with_the_store_flushed(self):
        # A one-minute flush interval: only the stop's own flush brings the newest image
        # (the live file's) into the main file.
        for sig in (signal.SIGTERM, signal.SIGINT):
            proc = subprocess.Popen(
                [self.node_binary(), "__name:=" + NODE, "_cell:=" + self.cell,
                 "_persist_file:=" + self.store, "_persist_interval:=60"],
                stdin=subprocess.DEVNULL)
            rospy.wait_for_service("/%s/write" % NODE, timeout=30)
            r = rospy.ServiceProxy("/%s/write" % NODE, WriteMemory)("R101", [int(sig)])
            self.assertTrue(r.success, r.message)
            proc.send_signal(sig)
            self.assertEqual(proc.wait(timeout=20), 0)  # not killed by the signal
            main, live = self.newest_slot(self.store), self.newest_slot(self.store + ".live")
            self.assertGreater(main[0], 0)
            self.assertEqual(main, live)
        # Right after the spawn: a clean stop, or (before main ran) the default action; the
        # store keeps what the last run flushed either way (test_cell.il recomputes R10 from
        # R11 and R12, which nothing writes here, so a clean run changes no retentive value).
        before = self.newest_slot(self.store)
        proc = subprocess.Popen(
            [self.node_binary(), "__name:=" + NODE, "_cell:=" + self.cell,
             "_persist_file:=" + self.store, "_persist_interval:=60"],
            stdin=subprocess.DEVNULL)
        proc.send_signal(signal.SIGTERM)
        self.assertIn(proc.wait(timeout=20), (0, -signal.SIGTERM))
        after = self.newest_slot(self.store)
        self.assertEqual(after[1], before[1])

    def kill(self, proc):
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(timeout=10)
        # The dead node's services stay registered with the master until a new one takes
        # their names; wait_for_service after the restart then reaches the new node.

    def test_acknowledged_retentive_writes_survive_sigkill(self):
        proc = self.start()
        write = rospy.ServiceProxy("/%s/write" % NODE, WriteMemory)
        for address, values in [("R100", [11, 22, 33, 44]), ("M900", [1]), ("DD10", [123456789]),
                                ("R3900", [77])]:
            r = write(address, values)
            self.assertTrue(r.success, r.message)
        self.kill(proc)  # at once: the replies above are the only promise

        proc = self.start()
        try:
            read = rospy.ServiceProxy("/%s/read" % NODE, ReadMemory)
            self.assertEqual(list(read("R100", 4).values), [11, 22, 33, 44])
            self.assertEqual(list(read("M900", 1).values), [1])  # M800-M1399 retentive by default
            self.assertEqual(list(read("DD10", 1).values), [123456789])
            self.assertEqual(list(read("R3900", 1).values), [0])  # outside R0-R3839: cleared
        finally:
            proc.send_signal(signal.SIGINT)
            proc.wait(timeout=10)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "node_restart_test", NodeRestartTest)
