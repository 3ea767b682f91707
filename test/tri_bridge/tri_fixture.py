#!/usr/bin/python3
"""rostest fixture: `plc_cell run --tri-tcp 127.0.0.1:PORT` with a program. tri_bridge
connects to it (retrying until it listens). Killed on shutdown."""
import os
import subprocess
import sys

import rospy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), ".."))
from tool_path import find_tool  # noqa: E402


def main():
    rospy.init_node("tri_bridge_fixture")
    program = rospy.get_param("~program")
    tcp = rospy.get_param("~tri_tcp")
    proc = subprocess.Popen([find_tool(), "run", "--program", program, "--tri-tcp", tcp])
    rospy.loginfo("fixture: plc_cell run serving the TRi host link on %s", tcp)
    rospy.spin()
    proc.terminate()
    try:
        proc.wait(timeout=5)
    except subprocess.TimeoutExpired:
        proc.kill()
    return 0


if __name__ == "__main__":
    sys.exit(main())
