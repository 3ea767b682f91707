"""`rosrun plc_cell plc_cell` finds the tool once and says nothing on stderr: the workspace
lives inside the package (.build/ws), and its source space must not lead rosrun's search
(`find -L` over the package) back into the package, a loop find warns about."""
import os
import subprocess
import sys

# realpath: run from the workspace, this file is reached through its links to the package.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
from pyutil import ROOT, devel  # noqa: E402


def rosrun(*args):
    cmd = "source %s/setup.bash && rosrun plc_cell %s" % (devel(), " ".join(args))
    return subprocess.run(["bash", "-c", cmd], stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, universal_newlines=True, timeout=120)


def test_rosrun_finds_the_tool_once_without_warnings():
    p = rosrun("plc_cell", "check", "--config", os.path.join(ROOT, "examples", "conveyor", "conveyor.yaml"))
    assert p.stderr == "", p.stderr
    assert p.returncode == 0, p.stdout
    assert "[rosrun]" not in p.stdout, p.stdout  # no "non-unique executable" question

