#!/usr/bin/env python3
"""rostest fixture: a socat pty pair and `plc_cell run --fatek-serial` on one end.
The bridge opens the other end (it retries until the pty exists). Killed on shutdown."""
import os
import subprocess
import sys

import rospy
import roslib.packages


def main():
    rospy.init_node("fatek_bridge_fixture")
    d = rospy.get_param("~dir")
    program = rospy.get_param("~program")
    os.makedirs(d, exist_ok=True)
    a, b = os.path.join(d, "A"), os.path.join(d, "B")
    socat = subprocess.Popen(["socat", "-d", "-d", "pty,raw,echo=0,link=" + a, "pty,raw,echo=0,link=" + b],
                             stderr=subprocess.PIPE, universal_newlines=True)
    for line in socat.stderr:  # block until both ptys exist
        if "starting data transfer loop" in line:
            break
    tool = roslib.packages.find_node("plc_cell", "plc_cell")[0]
    run = subprocess.Popen([tool, "run", "--program", program, "--fatek-serial", a + ":115200:7E1",
                            "--station", "1"])
    rospy.loginfo("fixture: socat %s <-> %s, plc_cell run serving %s", a, b, a)
    rospy.on_shutdown(lambda: None)
    rospy.spin()
    for p in (run, socat):
        p.terminate()
        try:
            p.wait(timeout=5)
        except subprocess.TimeoutExpired:
            p.kill()
    for f in (a, b):
        if os.path.lexists(f):
            os.unlink(f)
    try:
        os.rmdir(d)
    except OSError:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
