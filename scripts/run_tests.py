#!/usr/bin/python3
"""Runs every test of the package (gtest and rostest, through catkin's run_tests
target) and totals the test cases from the JUnit XML files.

The last line is "N passed, N failed"; the exit status is non-zero on any failure,
and a test target that produced no results counts as a failure (a crash)."""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

# Its neighbour, also when a test loads this file as a module from elsewhere.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ros_loopback import loopback_env  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def expected_results():
    """Result files catkin writes for the tests that CMakeLists.txt and cmake/**/*.cmake declare
    (gtest, rostest, pytest)."""
    text = open(os.path.join(ROOT, "CMakeLists.txt")).read()
    for path in sorted(glob.glob(os.path.join(ROOT, "cmake", "**", "*.cmake"), recursive=True)):
        text += "\n" + open(path).read()
    names = ["gtest-%s.xml" % n for n in re.findall(r"catkin_add_gtest\((\w+)", text)]
    names += ["pytest-%s.xml" % n for n in re.findall(r"plc_cell_add_pytest\((\w+)", text)]
    for path in re.findall(r"add_rostest\(([\w/.]+)", text):
        names.append("rostest-%s.xml" % os.path.splitext(path)[0].replace("/", "_"))
    return names


def count(xml_path):
    """(passed, failed, names of failures) of one JUnit file.

    A suite can report errors that belong to no test case (a failing setUpClass, a test
    node that died): they count as failures, and so does a file with no test case at all.

    A rostest writes two files: its test node's own results (rosunit-<test>.xml), counted
    like any other, and a wrapper (rostest-<file>.xml) with one case per test node that
    passes when the node wrote its results. A passing wrapper case counts nothing (its
    tests are counted from their own file); a failing one is a failure (the node crashed,
    timed out or wrote no results), since there is then nothing else to count."""
    passed, failed, names = 0, 0, []
    root = ET.parse(xml_path).getroot()
    wrapper = os.path.basename(xml_path).startswith("rostest-")
    for case in root.iter("testcase"):
        bad = case.find("failure") is not None or case.find("error") is not None
        skipped = case.find("skipped") is not None
        if bad or skipped:  # a skipped check is a defect here, not a pass
            failed += 1
            names.append(case.get("classname", "") + "." + case.get("name", ""))
        elif not wrapper:
            passed += 1
    suites = [root] if root.tag == "testsuite" else list(root.iter("testsuite"))
    reported = sum(int(s.get("errors", "0") or 0) + int(s.get("failures", "0") or 0) for s in suites)
    if reported > failed:
        names.append("%d error(s) outside any test case (setUpClass, a crashed test node)" % (reported - failed))
        failed = reported
    if passed + failed == 0 and not (wrapper and any(True for _ in root.iter("testcase"))):
        failed = 1
        names.append("no test case ran")
    return passed, failed, names


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--workspace", required=True)
    ap.add_argument("--jobs", default="2")
    args = ap.parse_args()
    ws = os.path.abspath(args.workspace)
    results = os.path.join(ws, "build", "test_results", "plc_cell")
    shutil.rmtree(results, ignore_errors=True)
    cmd = ("source %s/devel/setup.bash && cd %s && catkin_make -j1 run_tests"
           % (ws, ws))
    # Every node and master of the tests is on loopback: no test depends on the hostname.
    env = loopback_env(dict(os.environ, ROS_HOME=os.path.join(ws, "ros_home"), PYTHONUNBUFFERED="1"))
    rc = subprocess.call(["bash", "-c", cmd], env=env, stdin=subprocess.DEVNULL)

    passed = failed = 0
    broken = []
    for name in expected_results():
        path = os.path.join(results, name)
        if not os.path.exists(path):
            failed += 1
            broken.append("%s: no results (the test crashed or did not run)" % name)
    for path in sorted(glob.glob(os.path.join(results, "*.xml"))):
        try:
            p, f, names = count(path)
        except ET.ParseError as e:
            failed += 1
            broken.append("%s: unreadable results (%s)" % (os.path.basename(path), e))
            continue
        passed += p
        failed += f
        broken += ["%s: %s" % (os.path.basename(path), n) for n in names]
    if rc != 0:
        broken.append("catkin_make run_tests exited with %d" % rc)
    print("")
    for b in broken:
        print("FAILED " + b)
    print("%d passed, %d failed" % (passed, failed))
    return 1 if (failed or rc != 0 or passed == 0) else 0


if __name__ == "__main__":
    sys.exit(main())
