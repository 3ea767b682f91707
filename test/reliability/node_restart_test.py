#!/usr/bin/python3
"""rostest: kill -9 of plc_node loses no acknowledged write to a retentive range."""
import os
import signal
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
