"""The suite started as a background job (`make test &`, nohup, a CI script): its shell
ignores SIGINT, and that is inherited across exec. The clean-stop test signals `plc_cell run`
right after its start, so it only means what it says if the test's children get the default
actions back (test/harness/child_process.h). Here it runs from such a parent, with SIGINT
and SIGTERM also blocked, and must pass within its limit."""
import os
import signal
import subprocess
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
from pyutil import ROOT, devel  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from process_tree import stop  # noqa: E402

LIMIT = 600  # s: the clean-stop test takes well under a minute on an idle machine


def as_a_background_job():
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGQUIT, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})


def test_the_clean_stop_test_passes_from_a_parent_that_ignores_sigint(tmp_path):
    xml = str(tmp_path / "results.xml")
    p = subprocess.Popen([os.path.join(devel(), "lib", "plc_cell", "reliability_tests"),
                          "--gtest_filter=CleanStop.*:ChildSignals.*", "--gtest_output=xml:" + xml],
                         cwd=ROOT, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         preexec_fn=as_a_background_job, start_new_session=True)
    try:
        out, _ = p.communicate(timeout=LIMIT)
    except subprocess.TimeoutExpired:
        stop(p)
        out, _ = p.communicate()
        raise AssertionError("the clean-stop test did not end within %d s:\n%s"
                             % (LIMIT, out.decode(errors="replace")[-4000:]))
    text = out.decode(errors="replace")
    assert p.returncode == 0, text[-4000:]
    cases = [c.get("classname") + "." + c.get("name") for c in ET.parse(xml).getroot().iter("testcase")]
    assert "CleanStop.SignalAtEveryStartUpMomentFlushesTheStore" in cases, cases
    assert "ChildSignals.StartWithDefaultActionsAndNothingBlocked" in cases, cases
