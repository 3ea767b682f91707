"""`make demo` on a built tree starts the demo without a catkin pass: only a changed
source sends it through catkin again."""
import os
import subprocess

# realpath: run from the workspace, this file is reached through its links to the package.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))


def dry_run(target):
    return subprocess.run(["make", "-n", target], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           universal_newlines=True, check=True).stdout


def test_demo_on_a_built_tree_skips_catkin():
    out = dry_run("demo")
    assert "roslaunch plc_cell cell_sim.launch" in out
    assert "catkin_make" not in out, "make demo would run catkin on a built tree:\n" + out


def test_a_changed_source_rebuilds_first():
    stamp = os.path.join(ROOT, ".build", "ws", ".built")
    src = os.path.join(ROOT, "src", "core", "plc.cpp")
    st = os.stat(stamp)
    try:
        os.utime(stamp, (st.st_atime, os.stat(src).st_mtime - 10))  # the stamp older than a source
        out = dry_run("demo")
        assert "build" in out and out.index("build") < out.index("roslaunch"), out
    finally:
        os.utime(stamp, (st.st_atime, st.st_mtime))
