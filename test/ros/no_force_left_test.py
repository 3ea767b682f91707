#!/usr/bin/python3
"""rostest, after a scenario run through fatek_bridge (scenario_real_time_bridge.test): the PLC
itself, asked over FATEK (command 43), has no point left forced among its first inputs,
outputs and relays. fatek_bridge publishes no ~forced, so this is seen from the PLC's side."""
import os
import subprocess
import sys
import unittest

import rospy
import rostest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from tool_path import find_tool  # noqa: E402


class NoForceLeft(unittest.TestCase):
    def test_no_point_is_forced(self):
        rospy.init_node("no_force_left", anonymous=True)
        endpoint = rospy.get_param("~fatek_tcp")
        for first in ("X0", "Y0", "M0"):
            out = subprocess.run([find_tool(), "fatek", "--tcp", endpoint, "disabled", first, "32"],
                                 capture_output=True, text=True, timeout=30)
            self.assertEqual(out.returncode, 0, out.stderr)
            forced = [line for line in out.stdout.splitlines() if line.split()[-1] != "enabled"]
            self.assertEqual(forced, [], out.stdout)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "no_force_left", NoForceLeft)
