"""A user's package made from the recipe of docs/testing-your-cell.md ("The same scenarios
as rostests"), test/user_package/my_cell_tests, builds in a scratch catkin workspace over
this one's devel space and runs its scenario as a rostest with `catkin_make run_tests`:
every case passes, one JUnit test case each; a copy with a wrong expectation fails with the
runner's report."""
import glob
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

# realpath: run from the workspace, this file is reached through its links to the package.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
from pyutil import ROOT, devel  # noqa: E402
PACKAGE = os.path.join(ROOT, "test", "user_package", "my_cell_tests")
CASES = ["start runs the motor, the lamp follows after 1 s", "stop stops the motor and the lamp"]


def run_tests(ws):
    """catkin_make run_tests in ws; the test cases of its results, name -> failure text or None."""
    cmd = ("source %s/setup.bash && cd %s && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 run_tests"
           % (devel(), ws))
    env = dict(os.environ, ROS_HOME=os.path.join(ws, "ros_home"))
    p = subprocess.run(["bash", "-c", cmd], env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, timeout=900, universal_newlines=True)
    assert p.returncode == 0, p.stdout[-4000:]
    cases = {}
    for path in glob.glob(os.path.join(ws, "build", "test_results", "my_cell_tests", "*.xml")):
        for case in ET.parse(path).getroot().iter("testcase"):
            bad = case.find("failure")
            if bad is None:
                bad = case.find("error")
            text = None if bad is None else (bad.get("message", "") + "\n" + (bad.text or ""))
            cases[case.get("name")] = text
    return cases, p.stdout


def case_results(cases, name):
    return [v for k, v in cases.items() if k.endswith(name)]


def test_a_users_package_runs_its_scenario_as_a_rostest():
    ws = tempfile.mkdtemp(prefix="my_cell_ws_")
    try:
        os.makedirs(os.path.join(ws, "src"))
        src = os.path.join(ws, "src", "my_cell_tests")
        shutil.copytree(PACKAGE, src)
        cases, out = run_tests(ws)
        for name in CASES:
            found = case_results(cases, name)
            assert found, "no result for the case '%s' in %s\n%s" % (name, sorted(cases), out[-3000:])
            assert all(f is None for f in found), "the case '%s' failed: %s" % (name, found)

        # A wrong expectation: the lamp a second late. The scenario is read when the test
        # runs, so the same build runs it again.
        scenario = os.path.join(src, "test", "my_cell.scenario.yaml")
        text = open(scenario).read()
        assert "between: [1s, 1.02s]" in text
        with open(scenario, "w") as f:
            f.write(text.replace("between: [1s, 1.02s]", "between: [2s, 2.02s]"))
        shutil.rmtree(os.path.join(ws, "build", "test_results"), ignore_errors=True)
        cases, out = run_tests(ws)
        failed = [f for f in case_results(cases, CASES[0]) if f]
        assert failed, "the wrong expectation passed: %s\n%s" % (cases, out[-3000:])
        assert "my_cell.scenario.yaml:" in failed[0] and "lamp" in failed[0], failed[0]
        assert all(f is None for f in case_results(cases, CASES[1])), cases
    finally:
        shutil.rmtree(ws, ignore_errors=True)
