"""scripts/run_tests.py's total: each test counted once, whatever files it wrote."""
import importlib.util
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
_spec = importlib.util.spec_from_file_location("run_tests", os.path.join(ROOT, "scripts", "run_tests.py"))
run_tests = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(run_tests)


def junit(d, name, cases, errors=0, failures=0):
    """A JUnit file as rosunit writes it: cases are (name, 'ok' | 'failure' | 'error')."""
    body = "".join('<testcase classname="c" name="%s" time="0.1">%s</testcase>'
                   % (n, "" if r == "ok" else '<%s message="m" type=""/>' % r) for n, r in cases)
    path = os.path.join(d, name)
    with open(path, "w") as f:
        f.write('<?xml version="1.0" encoding="utf-8"?><testsuite name="s" tests="%d" errors="%d" failures="%d">%s'
                '</testsuite>' % (len(cases), errors, failures, body))
    return path


def test_a_rostest_counts_its_own_tests_once():
    d = tempfile.mkdtemp()
    # plc_node.test with one test node of 3 cases: rostest writes the node's results and a
    # wrapper with one case "the node wrote results".
    own = junit(d, "rosunit-plc_node_test.xml", [("a", "ok"), ("b", "ok"), ("c", "ok")])
    wrapper = junit(d, "rostest-test_ros_plc_node.xml", [("testplc_node_test", "ok")])
    total = [sum(x) for x in zip(*[run_tests.count(p)[:2] for p in (own, wrapper)])]
    assert total == [3, 0]


def test_a_rostest_whose_node_wrote_nothing_is_one_failure():
    d = tempfile.mkdtemp()
    wrapper = junit(d, "rostest-test_ros_plc_node.xml", [("testplc_node_test", "failure")], failures=1)
    passed, failed, names = run_tests.count(wrapper)
    assert (passed, failed) == (0, 1)
    assert names == ["c.testplc_node_test"]


def test_a_failing_case_in_a_rostest_counts_once():
    d = tempfile.mkdtemp()
    own = junit(d, "rosunit-plc_node_test.xml", [("a", "ok"), ("b", "failure")], failures=1)
    wrapper = junit(d, "rostest-test_ros_plc_node.xml", [("testplc_node_test", "ok")])
    total = [sum(x) for x in zip(*[run_tests.count(p)[:2] for p in (own, wrapper)])]
    assert total == [1, 1]


def test_other_files_count_every_case_and_an_empty_one_fails():
    d = tempfile.mkdtemp()
    assert run_tests.count(junit(d, "gtest-core_tests.xml", [("a", "ok"), ("b", "ok")]))[:2] == (2, 0)
    assert run_tests.count(junit(d, "gtest-empty.xml", []))[:2] == (0, 1)


def _test(d, name, script, limit):
    t = run_tests.Test(name, ["bash", "-c", script], d, limit)
    return t


def _alive(pid):
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_a_hung_test_is_killed_at_its_limit_with_all_it_started_and_the_rest_runs():
    d = tempfile.mkdtemp()
    pids = os.path.join(d, "pids")
    # A test that hangs, with a grandchild that left for a session of its own (as a server
    # started with setsid does): both must go when the limit is reached.
    hung = _test(d, "gtest_hangs", "setsid sleep 600 & echo $! >> %s; echo $$ >> %s; sleep 600" % (pids, pids), 2)
    fine = _test(d, "gtest_fine", "echo fine", 60)
    lines = []
    done = run_tests.run_all([hung, fine], 1, os.path.join(d, "logs"), dict(os.environ), report=lines.append)
    assert [t.name for t in done] == ["gtest_hangs", "gtest_fine"]
    assert hung.timed_out and not fine.timed_out and fine.status == 0
    assert 2 <= hung.seconds < 30
    started = [int(p) for p in open(pids).read().split()]
    assert len(started) == 2 and not any(_alive(p) for p in started), started
    assert any("gtest_hangs" in line and "TIMEOUT" in line for line in lines), lines
    passed, failed, broken = run_tests.total(d, done, ["gtest-hangs.xml"])
    assert failed == 1
    assert broken == ["gtest_hangs: killed after its time limit of 2 s (log: %s)" % hung.log]


def test_result_files_are_named_as_catkin_names_them():
    assert run_tests.result_file("gtest_core_tests") == "gtest-core_tests.xml"
    assert run_tests.result_file("rostest_test_ros_plc_node.test") == "rostest-test_ros_plc_node.xml"
    assert run_tests.result_file("pytest_docs") == "pytest-docs.xml"


def test_the_longest_run_first_and_known_long_ones_before_unknown_ones():
    tests = [run_tests.Test(n, [], "/", 1) for n in ("gtest_a", "gtest_b", "gtest_fuzz_tests", "gtest_c")]
    assert [t.name for t in run_tests.order(tests, {"gtest_b": 5.0, "gtest_c": 50.0})] == \
        ["gtest_c", "gtest_b", "gtest_fuzz_tests", "gtest_a"]


def test_a_file_of_the_package_a_test_writes_is_found():
    d = tempfile.mkdtemp()
    git = lambda *a: subprocess.run(["git", "-C", d] + list(a), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                    check=True, timeout=60)
    git("init", "-q")
    open(os.path.join(d, "kept.il"), "w").write("END\n")
    open(os.path.join(d, "edited.il"), "w").write("END\n")
    git("add", ".")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-m", "x")
    open(os.path.join(d, "edited.il"), "w").write("ORG M1925\nEND\n")  # changed before the suite
    before = run_tests.tree_state(d)
    assert run_tests.changed_by_tests(before, run_tests.tree_state(d)) == []
    open(os.path.join(d, "edited.il"), "w").write("ORG M1924\nEND\n")  # ... and by a test
    open(os.path.join(d, "new.changes.jsonl"), "w").write("{}\n")
    os.remove(os.path.join(d, "kept.il"))
    assert run_tests.changed_by_tests(before, run_tests.tree_state(d)) == ["edited.il", "kept.il", "new.changes.jsonl"]
