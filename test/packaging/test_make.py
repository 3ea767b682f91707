"""`make demo` on a built tree starts the demo without a catkin pass: only a changed
source sends it through catkin again, and then only for what the demo runs."""
import os
import re
import subprocess

# realpath: run from the workspace, this file is reached through its links to the package.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))


def dry_run(target, *settings):
    return subprocess.run(["make", "-n", target] + list(settings), cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, check=True).stdout


def make_list(name):
    text = open(os.path.join(ROOT, "Makefile"), encoding="utf-8").read().replace("\\\n", " ")
    return re.search(r"^%s\s*:=(.*)$" % name, text, re.M).group(1).split()


def test_demo_on_a_built_tree_skips_catkin():
    out = dry_run("demo")
    assert "roslaunch plc_cell cell_sim.launch" in out
    assert "catkin_make" not in out, "make demo would run catkin on a built tree:\n" + out


def test_demo_line_runs_the_example_line_with_its_monitor():
    out = dry_run("demo", "LINE=1", "MONITOR=127.0.0.1:9091")
    assert "plc_cell run --line examples/line/line.line.yaml --http-tcp 127.0.0.1:9091 --http-writable all" in out, out
    assert "roslaunch plc_cell" not in out, out


def test_a_changed_source_rebuilds_the_demo_only_first():
    stamp = os.path.join(ROOT, ".build", "ws", ".built-demo")
    src = os.path.join(ROOT, "src", "core", "plc.cpp")
    st = os.stat(stamp)
    try:
        os.utime(stamp, (st.st_atime, os.stat(src).st_mtime - 10))  # the stamp older than a source
        out = dry_run("demo")
    finally:
        os.utime(stamp, (st.st_atime, st.st_mtime))
    catkin = [line for line in out.splitlines() if "catkin_make" in line]
    assert len(catkin) == 1 and out.index("catkin_make") < out.index("roslaunch plc_cell cell_sim.launch"), out
    # Only the demo's targets: no `all` (benchmarks), no `tests` (gtests, fuzz builds), and
    # the messages in the two languages the demo uses.
    targets = catkin[0].split("-DCATKIN_ENABLE_TESTING=$testing")[1].split("2>&1")[0].split()
    assert targets == ["plc_cell_generate_messages_cpp", "plc_cell_generate_messages_py", "plc_node",
                       "plc_cell_tool"], catkin[0]


def test_demo_installs_no_test_package():
    out = dry_run("demo")
    listed = [line for line in out.splitlines() if "dpkg-query" in line]
    assert listed, out
    for pkg in make_list("TEST_PACKAGES"):
        assert not re.search(r"(?<![\w.+-])%s(?![\w.+-])" % re.escape(pkg), listed[0]), \
            "make demo checks for the test package %s" % pkg
    for pkg in make_list("DEMO_PACKAGES"):
        assert pkg in listed[0].split(), "make demo does not install %s" % pkg
