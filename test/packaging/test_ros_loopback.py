"""The tests, the doc tests and `make demo` run on loopback, whether or not the machine's own
hostname resolves (many minimal containers' /etc/hosts lack it): ROS_HOSTNAME=localhost where
neither ROS_HOSTNAME nor ROS_IP is set (scripts/ros_loopback.py). The rostest below runs on a
machine whose hostname resolves nowhere: a UTS namespace of its own (unshare) with a name no
resolver knows, in the environment scripts/run_tests.py gives every test."""
import os
import shutil
import subprocess
import sys
import tempfile

# realpath: run from the workspace, this file is reached through its links to the package.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
from pyutil import ROOT, devel  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from ros_loopback import loopback_env, unreachable  # noqa: E402

NOWHERE = "plc-cell-host-that-resolves-nowhere"


def bare_env(scratch):
    """The environment with no ROS_HOSTNAME or ROS_IP, and results and logs in scratch."""
    env = dict(os.environ, ROS_HOME=scratch, ROS_TEST_RESULTS_DIR=os.path.join(scratch, "results"))
    for k in ("ROS_HOSTNAME", "ROS_IP", "ROS_MASTER_URI"):
        env.pop(k, None)
    return env


def rostest_on_a_host_that_does_not_resolve(env):
    script = ("hostname %s && ! getent hosts %s >/dev/null && source %s/setup.bash && "
              "rostest --text plc_cell plc_node.test" % (NOWHERE, NOWHERE, devel()))
    # As root (make test-fresh, in a chroot where no user namespace may be made) a UTS
    # namespace alone; otherwise one inside a user namespace of its own.
    unshare = ["unshare", "--uts"] if os.geteuid() == 0 else ["unshare", "--map-root-user", "--uts"]
    return subprocess.run(unshare + ["bash", "-c", script], env=env,
                          stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=600)


def test_loopback_only_where_no_name_is_given():
    assert loopback_env({})["ROS_HOSTNAME"] == "localhost"
    assert loopback_env({"ROS_HOSTNAME": ""})["ROS_HOSTNAME"] == "localhost"
    assert loopback_env({"ROS_HOSTNAME": "cell7"})["ROS_HOSTNAME"] == "cell7"
    assert "ROS_HOSTNAME" not in loopback_env({"ROS_IP": "192.168.1.20"})


def test_a_rostest_passes_where_the_hostname_does_not_resolve():
    scratch = tempfile.mkdtemp(prefix="plc_cell_loopback_")
    try:
        bare = bare_env(scratch)
        # The machine as the defect needs it: ROS on its own names cannot reach itself.
        failed = rostest_on_a_host_that_does_not_resolve(bare)
        assert failed.returncode != 0, failed.stdout[-3000:]
        assert "Unable to contact my own server" in failed.stdout, failed.stdout[-3000:]
        ok = rostest_on_a_host_that_does_not_resolve(loopback_env(bare))
        assert ok.returncode == 0, ok.stdout[-4000:]
        assert "SUMMARY" in ok.stdout and "* RESULT: SUCCESS" in ok.stdout, ok.stdout[-4000:]
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def test_the_demo_gives_a_hint_when_the_master_cannot_reach_itself():
    env = dict(os.environ, ROS_HOSTNAME=NOWHERE)
    env.pop("ROS_IP", None)
    assert "does not resolve" in unreachable(env)
    p = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "ros_loopback.py")], env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, timeout=60)
    assert p.returncode == 2
    assert "Traceback" not in p.stderr
    assert "ROS_HOSTNAME '%s' does not resolve" % NOWHERE in p.stderr, p.stderr
    assert "export ROS_HOSTNAME=localhost" in p.stderr, p.stderr
    # make demo runs that check before roslaunch, and stops on it.
    demo = subprocess.run(["make", "-n", "demo"], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, check=True).stdout
    assert demo.index("scripts/ros_loopback.py") < demo.index("roslaunch plc_cell cell_sim.launch"), demo
