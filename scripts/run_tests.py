#!/usr/bin/python3
"""Runs every test of the package (gtest, rostest and pytest, as catkin declares them) and
totals the test cases from the JUnit XML files.

Each test executable or file runs in a session of its own, --jobs at a time, the longest
first (by the last run's times where known), with a time limit: past it, the test and
everything it started are killed, and it counts as a failure that names it and the limit.
The rest of the suite goes on. Each test's output goes to a log beside its results; a
failing test's last lines are printed.

The last line is "N passed, N failed"; the exit status is non-zero on any failure, and a
test that produced no results counts as a failure (a crash)."""
import argparse
import glob
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

# Its neighbours, also when a test loads this file as a module from elsewhere.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from process_tree import signal_tree, stop  # noqa: E402
from ros_loopback import loopback_env  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Seconds a test may take before it is killed: about three times its time on a loaded
# 2-core machine (docs/testing.md, "The suite's own time"), so that only a hang reaches it.
LIMIT = 900
LIMITS = {"gtest_fuzz_tests": 1800, "gtest_core_tests": 1800}
# Known to be long, started first on a machine that has no times of its own yet.
LONG_FIRST = ["gtest_fuzz_tests", "gtest_core_tests", "pytest_docs", "pytest_monitor_page",
              "rostest_test_ros_scenario_line_virtual_time.test", "rostest_test_ros_service_fuzz.test",
              "rostest_test_ros_scenario_oven.test", "gtest_reliability_tests"]
TIMES_FILE = "durations.json"  # beside the results: each test's seconds in the last run
PREFIX = "_ctest_plc_cell_"


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


def result_file(name):
    """The JUnit file catkin's wrapper checks for: gtest_core_tests -> gtest-core_tests.xml,
    rostest_test_ros_plc_node.test -> rostest-test_ros_plc_node.xml."""
    kind, rest = name.split("_", 1)
    return "%s-%s.xml" % (kind, rest[:-5] if rest.endswith(".test") else rest)


class Test:
    def __init__(self, name, argv, cwd, limit):
        self.name, self.argv, self.cwd, self.limit = name, argv, cwd, limit
        self.proc = self.log = None
        self.started = self.seconds = 0.0
        self.status = None
        self.timed_out = False


def discover(build_dir, limit=None):
    """The tests catkin declared, as CTest knows them: each one's command (catkin's wrapper,
    which checks that the test wrote its results) and working directory."""
    out = subprocess.run(["ctest", "--show-only=json-v1"], cwd=build_dir, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, universal_newlines=True, timeout=120)
    if out.returncode != 0:
        raise SystemExit("ctest could not list the tests in %s:\n%s" % (build_dir, out.stderr))
    tests = []
    for t in json.loads(out.stdout).get("tests", []):
        if not t["name"].startswith(PREFIX):
            continue
        name = t["name"][len(PREFIX):]
        props = {p["name"]: p["value"] for p in t.get("properties", [])}
        tests.append(Test(name, t["command"], props.get("WORKING_DIRECTORY", build_dir),
                          limit or LIMITS.get(name, LIMIT)))
    return tests


def order(tests, times):
    """Longest first (LPT): the last run's seconds, else the known long ones first."""
    def key(t):
        if t.name in times:
            return (0, -times[t.name])
        return (1, LONG_FIRST.index(t.name) if t.name in LONG_FIRST else len(LONG_FIRST), t.name)
    return sorted(tests, key=key)


def tail(path, lines=60):
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError:
        return ""


def run_all(tests, jobs, log_dir, env, report=print):
    """Runs tests, `jobs` at a time, each with its limit; fills in status, seconds, timed_out."""
    os.makedirs(log_dir, exist_ok=True)
    waiting, running, done = list(tests), [], []
    try:
        while waiting or running:
            while waiting and len(running) < jobs:
                t = waiting.pop(0)
                t.log = os.path.join(log_dir, t.name + ".log")
                with open(t.log, "wb") as log:
                    t.proc = subprocess.Popen(t.argv, cwd=t.cwd, env=env, stdin=subprocess.DEVNULL, stdout=log,
                                              stderr=subprocess.STDOUT, start_new_session=True)
                t.started = time.monotonic()
                running.append(t)
            time.sleep(0.2)
            for t in list(running):
                elapsed = time.monotonic() - t.started
                if t.proc.poll() is None and elapsed < t.limit:
                    continue
                if t.proc.returncode is None:
                    t.timed_out = True
                    stop(t.proc, grace=5, first=signal.SIGTERM)
                else:  # whatever it left running in its group goes with it
                    stop(t.proc)
                t.status, t.seconds = t.proc.returncode, time.monotonic() - t.started
                running.remove(t)
                done.append(t)
                verdict = "TIMEOUT" if t.timed_out else "ok" if t.status == 0 else "FAILED (status %s)" % t.status
                report("[%3d/%d] %-45s %7.1f s  %s" % (len(done), len(tests), t.name, t.seconds, verdict))
                if t.status != 0 or t.timed_out:
                    report("---- last lines of %s ----\n%s----" % (t.log, tail(t.log)))
    finally:  # Ctrl-C or SIGTERM of the runner: nothing it started stays behind
        for t in running:
            signal_tree(t.proc.pid, signal.SIGKILL)
            t.proc.wait()
    return done


def tree_state(root):
    """{path: hash of its content, or None when deleted} of every file of the package that
    git sees as changed or new (ignored files left out); None outside a git checkout. The
    same before and after the suite, or a test wrote into the package."""
    try:
        out = subprocess.run(["git", "-C", root, "status", "--porcelain=v1", "-z", "--untracked-files=all"],
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return None
    if out.returncode != 0:
        return None
    state, entries = {}, out.stdout.split(b"\0")
    i = 0
    while i < len(entries):
        entry = entries[i]
        i += 1
        if len(entry) < 4:
            continue
        if entry[:2].strip(b" ") and entry[0:1] in b"RC":  # a rename names its old path next
            i += 1
        path = entry[3:].decode(errors="replace")
        try:
            with open(os.path.join(root, path), "rb") as f:
                state[path] = hashlib.sha1(f.read()).hexdigest()
        except OSError:
            state[path] = None
    return state


def changed_by_tests(before, after):
    if before is None or after is None:
        return []
    return sorted(p for p in set(before) | set(after) if before.get(p, "unchanged") != after.get(p, "unchanged"))


def total(results, done, expected):
    """(passed, failed, lines naming each failure)."""
    passed = failed = 0
    broken = []
    for t in done:
        if t.timed_out:
            failed += 1
            broken.append("%s: killed after its time limit of %d s (log: %s)" % (t.name, t.limit, t.log))
    timed_out_files = {result_file(t.name) for t in done if t.timed_out}
    for name in expected:
        if name not in timed_out_files and not os.path.exists(os.path.join(results, name)):
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
    return passed, failed, broken


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--workspace", required=True)
    ap.add_argument("--jobs", type=int, default=4)
    ap.add_argument("--limit", type=int, help="every test's time limit in seconds (default: per test, %d)" % LIMIT)
    ap.add_argument("-k", dest="only", help="only the tests whose names contain this text")
    args = ap.parse_args()
    ws = os.path.abspath(args.workspace)
    build = os.path.join(ws, "build")
    results = os.path.join(build, "test_results", "plc_cell")
    times_path = os.path.join(build, "test_results", TIMES_FILE)
    try:
        times = json.load(open(times_path))
    except (OSError, ValueError):
        times = {}
    shutil.rmtree(results, ignore_errors=True)
    os.makedirs(results)
    tests = [t for t in discover(build, args.limit) if not args.only or args.only in t.name]
    if not tests:
        raise SystemExit("no tests found in %s (was it built with make build?)" % build)
    # Every node and master of the tests is on loopback: no test depends on the hostname.
    env = loopback_env(dict(os.environ, ROS_HOME=os.path.join(ws, "ros_home"), PYTHONUNBUFFERED="1"))
    before = tree_state(ROOT)
    t0 = time.monotonic()
    print("== %d tests, %d at a time (logs in %s)" % (len(tests), args.jobs, os.path.join(results, "logs")))
    sys.stdout.flush()
    done = run_all(order(tests, times), args.jobs, os.path.join(results, "logs"), env,
                   report=lambda line: print(line, flush=True))
    wall = time.monotonic() - t0
    times.update({t.name: round(t.seconds, 1) for t in done if not t.timed_out})
    with open(times_path, "w") as f:
        json.dump(times, f, indent=1, sort_keys=True)
    chosen = {result_file(t.name) for t in tests}
    expected = [e for e in expected_results() if not args.only or e in chosen]
    passed, failed, broken = total(results, done, expected)
    written = changed_by_tests(before, tree_state(ROOT))
    if written:  # a test writes in a folder of its own, never into the package
        failed += 1
        broken.append("the tests changed the package's own files: %s" % ", ".join(written))
    busy = sum(t.seconds for t in done)
    print("\n== the tests took %.0f s of wall time, %.0f s of test time on %d workers; the longest:"
          % (wall, busy, args.jobs))
    for t in sorted(done, key=lambda t: -t.seconds)[:12]:
        print("   %-45s %7.1f s" % (t.name, t.seconds))
    print("")
    for b in broken:
        print("FAILED " + b)
    print("%d passed, %d failed" % (passed, failed))
    return 1 if (failed or passed == 0) else 0


if __name__ == "__main__":
    sys.exit(main())
