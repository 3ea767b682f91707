"""scripts/run_tests.py's total: each test counted once, whatever files it wrote."""
import importlib.util
import os
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
