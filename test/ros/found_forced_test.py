#!/usr/bin/python3
"""rostest: the demo's hardware scenario through fatek_bridge leaves a point the engineer had
forced as it was found. The bridge reads which points are forced from the PLC on request
(~read_forced, FATEK command 43), so the scenario runner knows that the stop button was found
forced ON: the cases force it as they need, and the restore forces it ON again instead of
releasing it. Bad requests to ~read_forced are answered with the reason and change nothing."""
import os
import subprocess
import sys
import time
import unittest

import rospy
import rostest

from plc_cell.srv import ForceDiscrete, ReadForced, ReadMemory, ReleaseDiscrete

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from tool_path import find_tool  # noqa: E402

NODE = "/fatek_bridge/"
SCENARIO = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                        "examples", "conveyor", "conveyor.hardware.scenario.yaml")
RUNNER_LIMIT = 240  # s: the scenario takes about 15 s of wall-clock time


class FoundForcedTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("found_forced_test", anonymous=True)
        for name in ("force", "release", "read", "read_forced"):
            rospy.wait_for_service(NODE + name, timeout=30)
        cls.force = rospy.ServiceProxy(NODE + "force", ForceDiscrete)
        cls.release = rospy.ServiceProxy(NODE + "release", ReleaseDiscrete)
        cls.read = rospy.ServiceProxy(NODE + "read", ReadMemory)
        cls.read_forced = rospy.ServiceProxy(NODE + "read_forced", ReadForced)
        # The bridge may have started before the PLC listened: it connects on a later try.
        deadline = time.monotonic() + 30
        while not cls.read_forced([]).success:
            if time.monotonic() > deadline:
                raise AssertionError("fatek_bridge not connected to the PLC within 30 s: " + cls.read_forced([]).message)
            time.sleep(0.1)  # polling the bridge's link, not waiting for a result

    def forced(self, *points):
        r = self.read_forced(list(points))
        self.assertTrue(r.success, r.message)
        return list(r.forced)

    def test_1_bad_requests_are_refused_with_the_reason(self):
        for points, why in ((["R0"], "only a single discrete"), (["no_such_point"], "no_such_point"),
                            (["X0", "Y9999"], "Y9999")):
            r = self.read_forced(points)
            self.assertFalse(r.success, points)
            self.assertIn(why, r.message)
            self.assertEqual(list(r.forced), [])
        self.assertEqual(self.forced(), [])

    def test_2_a_point_found_forced_is_forced_as_found_after_the_scenario(self):
        self.assertEqual(self.forced("X1", "stop_button", "X0"), [False, False, False])
        self.assertTrue(self.force("stop_button", True).success)  # the engineer's: released (NC)
        self.assertEqual(self.forced("X1", "X0", "X2", "X3"), [True, False, False, False])
        runner = subprocess.run(
            [find_tool("scenario_runner"), "_scenario:=" + SCENARIO, "_node:=" + NODE.rstrip("/"),
             "_real_time:=true", "_tolerance:=1", "__name:=found_forced_runner"],
            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=RUNNER_LIMIT)
        out = runner.stdout.decode(errors="replace")
        self.assertEqual(runner.returncode, 0, out[-6000:])
        self.assertIn("the PLC is as it was found", out)
        self.assertNotIn("says not which points are forced", out)
        self.assertEqual(self.forced("X1", "X0", "X3", "X4"), [True, False, False, False], out[-3000:])
        self.assertEqual(list(self.read("X1", 1).values), [1], "forced ON, as found")
        r = self.release("X1")
        self.assertEqual(list(r.released), ["X1"])
        self.assertEqual(self.forced("X1"), [False])


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "found_forced_test", FoundForcedTest)
