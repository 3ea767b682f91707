"""The install space works on its own. The built workspace is installed into a scratch prefix
(`cmake --install` with DESTDIR: what `catkin_make install` does after its build, staged,
without reconfiguring or building again), then plc_node is started with roslaunch and the tool with rosrun in an environment
that knows only that prefix: every executable and library comes from it. Only the headers of
the exported layers are installed."""
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import xmlrpc.client

import pytest

# realpath: run from the workspace, this file is reached through its links to the package.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
from pyutil import ROOT, devel, free_port  # noqa: E402
EXPORTED = {"core", "io", "config", "timeline", "hsc", "temp", "motion", "sim"}


def configured_prefix(build):
    with open(os.path.join(build, "CMakeCache.txt")) as f:
        return re.search(r"^CMAKE_INSTALL_PREFIX:PATH=(.*)$", f.read(), re.M).group(1)


class InstallSpace:
    def __init__(self):
        self.scratch = tempfile.mkdtemp(prefix="plc_cell_install_")
        build = os.path.join(os.path.dirname(devel()), "build")
        # A staged install (DESTDIR) of the built tree: every file, catkin's setup files
        # included, lands under the scratch folder; the tree is neither reconfigured nor built.
        root = os.path.join(self.scratch, "root")
        self.prefix = root + configured_prefix(build)
        p = subprocess.run(["cmake", "--install", build], env=dict(os.environ, DESTDIR=root),
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=600)
        assert p.returncode == 0, p.stdout[-3000:]
        self.port = free_port()
        # Nothing of the devel space or of the caller's ROS setup: only the system and the prefix.
        self.env = {"PATH": "/usr/bin:/bin", "HOME": os.environ.get("HOME", self.scratch), "LANG": "C.UTF-8",
                    "ROS_HOME": os.path.join(self.scratch, "ros_home"), "ROS_HOSTNAME": "localhost",
                    "ROS_MASTER_URI": "http://localhost:%d" % self.port}

    def shell(self, cmd):
        # local_setup.bash: this install space alone, not the workspaces it was configured over
        # (setup.bash would chain to the devel space when the build had it sourced).
        return ["bash", "-c", "source %s/local_setup.bash && %s" % (self.prefix, cmd)]

    def run(self, cmd):
        return subprocess.run(self.shell(cmd), env=self.env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, universal_newlines=True, timeout=300)

    def close(self):
        shutil.rmtree(self.scratch, ignore_errors=True)


@pytest.fixture(scope="module")
def space():
    s = InstallSpace()  # one install for the module's tests
    yield s
    s.close()


def test_the_install_space_runs_plc_node_and_the_tool_alone(space):
    ws = os.path.dirname(devel())
    env = space.run("echo $CMAKE_PREFIX_PATH; echo $LD_LIBRARY_PATH; echo $ROS_PACKAGE_PATH; "
                    "rospack find plc_cell")
    assert env.returncode == 0, env.stderr
    for line in env.stdout.split("\n")[:3]:
        for entry in filter(None, line.split(":")):
            assert not entry.startswith(ROOT), "%s: the source tree or %s in the environment" % (entry, ws)
    # Nothing installed leads back out of the install space (a link to the source tree).
    for top, dirs, files in os.walk(space.prefix):
        for name in dirs + files:
            path = os.path.join(top, name)
            if os.path.islink(path):
                assert os.path.realpath(path).startswith(space.prefix + "/"), "%s -> %s" % (path, os.readlink(path))
    assert env.stdout.split("\n")[3] == os.path.join(space.prefix, "share", "plc_cell")

    # The tool with rosrun, on an example installed with the package.
    tool = space.run("rosrun plc_cell plc_cell check --config $(rospack find plc_cell)/examples/conveyor/conveyor.yaml")
    assert tool.returncode == 0, tool.stdout + tool.stderr
    assert tool.stderr == "", tool.stderr

    # plc_node with roslaunch (its own master on a private port), until its services are up.
    log_path = os.path.join(space.scratch, "roslaunch.log")
    with open(log_path, "w") as log:
        launch = subprocess.Popen(space.shell("exec roslaunch plc_cell cell_sim.launch"), env=space.env,
                                  stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT)
    try:
        up = space.run("/usr/bin/python3 -c \"import rospy; rospy.init_node('wait', anonymous=True); rospy.wait_for_service('/plc_node/read', timeout=120)\"")
        with open(log_path) as f:
            output = f.read()
        assert up.returncode == 0, up.stderr + output[-3000:]
        uri = xmlrpc.client.ServerProxy(space.env["ROS_MASTER_URI"]).lookupNode("/test", "/plc_node")[2]
        pid = xmlrpc.client.ServerProxy(uri).getPid("/test")[2]
        exe = os.readlink("/proc/%d/exe" % pid)
        assert exe == os.path.join(space.prefix, "lib", "plc_cell", "plc_node"), exe
        with open("/proc/%d/maps" % pid) as f:
            libs = set(re.findall(r"(/\S*libplc_cell\S*\.so\S*)", f.read()))
        assert libs, "plc_node loaded none of the package's libraries"
        assert all(lib.startswith(space.prefix + "/") for lib in libs), sorted(libs)
        assert any("libplc_cell_timeline" in lib for lib in libs), sorted(libs)
    finally:
        # SIGTERM: roslaunch stops its nodes and master (they run in sessions of their own);
        # SIGINT may be ignored by a process started in the background.
        launch.send_signal(signal.SIGTERM)
        try:
            launch.wait(timeout=60)
        except subprocess.TimeoutExpired:
            launch.kill()
            launch.wait()


def test_only_the_exported_layers_headers_are_installed(space):
    include = os.path.join(space.prefix, "include", "plc_cell")
    layers = {d for d in os.listdir(include) if os.path.isdir(os.path.join(include, d))}
    assert layers == EXPORTED, sorted(layers)
    # Each installed header finds every package header it includes in the install space.
    for layer in layers:
        for folder, _, names in os.walk(os.path.join(include, layer)):  # core/native/ too
            for name in names:
                header = os.path.relpath(os.path.join(folder, name), include)
                with open(os.path.join(folder, name)) as f:
                    for inc in re.findall(r'#include "(plc_cell/[^"]+)"', f.read()):
                        assert os.path.exists(os.path.join(space.prefix, "include", inc)), \
                            "%s includes %s, which is not installed" % (header, inc)
