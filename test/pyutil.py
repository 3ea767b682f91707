"""What the pytest-based tests share (the browser, install and doc tests, the packaging
ones): the repository, the devel space they run against, a free loopback port, and stopping
a process they started in a session of its own. A test reaches this module with
sys.path.insert(0, <the test folder>) first, as the rostest scripts reach latest_message."""
import os
import signal
import socket
import subprocess

# realpath: run from the workspace, the tests are reached through its links to the package.
ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))


def devel():
    """The devel space: PLC_CELL_LIB_DIR's parent under the package's run_tests, else the
    repository's own build (make build)."""
    lib = os.environ.get("PLC_CELL_LIB_DIR")
    return os.path.dirname(lib) if lib else os.path.join(ROOT, ".build", "ws", "devel")


def free_port():
    """A TCP port on 127.0.0.1 that nothing listens on now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def stop(p, grace=15):
    """Stops p, started with start_new_session=True, and whatever it started: SIGINT to its
    process group (a user's Ctrl-C: servers save and close) for up to grace seconds, then
    SIGKILL."""
    for sig, limit in ((signal.SIGINT, grace), (signal.SIGKILL, 5)):
        try:
            os.killpg(p.pid, sig)
        except ProcessLookupError:
            return
        try:
            p.wait(timeout=limit)
            return
        except subprocess.TimeoutExpired:
            continue
