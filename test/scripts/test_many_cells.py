"""bench/many_cells.py stops what it started on every way out: a cell that does not load,
and a SIGTERM in the middle of a measurement. It also sets up the ROS environment from
--workspace itself, so it runs from a shell that sourced nothing.

Every process it starts inherits a marker in its environment; after the bench has ended,
no process with that marker may be left."""
import os
import signal
import subprocess
import sys
import time
import uuid

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
from pyutil import ROOT, devel  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from process_tree import stop, wait_until  # noqa: E402

BENCH = os.path.join(ROOT, "bench", "many_cells.py")
LIMIT = 180  # s: every wait here is bounded by this


def marked(marker):
    """pids of the live processes whose environment holds the marker (zombies excluded)."""
    out = []
    for d in os.listdir("/proc"):
        if not d.isdigit() or int(d) == os.getpid():
            continue
        try:
            with open("/proc/%s/environ" % d, "rb") as f:
                if ("PLC_CELL_BENCH_MARK=" + marker).encode() not in f.read().split(b"\0"):
                    continue
            with open("/proc/%s/stat" % d) as f:
                if f.read().rsplit(")", 1)[1].split()[0] == "Z":
                    continue
        except OSError:
            continue
        out.append(int(d))
    return out


def start(marker, *args):
    # Nothing sourced: only what a fresh login shell has, and the marker.
    env = {"PATH": "/usr/bin:/bin", "HOME": os.environ.get("HOME", "/root"), "PLC_CELL_BENCH_MARK": marker}
    return subprocess.Popen(["/usr/bin/python3", BENCH, "--workspace", os.path.dirname(devel())] + list(args),
                            env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            start_new_session=True)


def finish(p):
    try:
        out, _ = p.communicate(timeout=LIMIT)
    except subprocess.TimeoutExpired:
        stop(p)
        raise AssertionError("many_cells.py did not end within %d s" % LIMIT)
    return out.decode(errors="replace")


def described(pids):
    """Each pid with its command line: which process was left behind."""
    out = []
    for pid in pids:
        try:
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                out.append("%s: %s" % (pid, f.read().replace(b"\0", b" ").decode(errors="replace").strip()))
        except OSError:
            out.append("%s: (gone)" % pid)
    return "\n".join(out)


def test_a_cell_that_does_not_load_fails_with_its_reason_and_leaves_nothing():
    marker = uuid.uuid4().hex
    p = start(marker, "--cells", "1", "--ways", "nodelets", "--settle", "0", "--seconds", "1",
              "--cell", "/nonexistent/cell.yaml")
    out = finish(p)
    assert p.returncode != 0, out
    assert "the manager did not load /cell_0/plc_node" in out, out
    assert "cannot open the cell config" in out, out  # the manager's own log says why
    left = marked(marker)
    assert left == [], "left behind:\n%s\n%s" % (described(left), out)


def test_a_sigterm_during_the_measurement_leaves_nothing():
    marker = uuid.uuid4().hex
    p = start(marker, "--cells", "2", "--ways", "nodes", "--settle", "0", "--seconds", "600")
    # The master, the bench and two plc_node processes: the measurement is under way.
    wait_until(lambda: len(marked(marker)) >= 4, LIMIT, "the bench's master and two cells", p)
    p.send_signal(signal.SIGTERM)
    out = finish(p)
    assert p.returncode != 0, out
    deadline = time.monotonic() + 10  # SIGKILLed processes may still be ending
    while marked(marker) and time.monotonic() < deadline:
        time.sleep(0.1)
    left = marked(marker)
    assert left == [], "left behind:\n%s\n%s" % (described(left), out)


def test_a_child_the_bookkeeping_never_saw_is_stopped_at_the_end():
    """A SIGTERM can land between a child's start and the bench's record of it (Started
    entered into its ExitStack): the bench's last word, stop_children(), still finds it, as
    its child, and stops it with its own children."""
    marker = uuid.uuid4().hex
    script = ("import subprocess, sys; sys.path.insert(0, %r)\n"
              "from process_tree import stop_children\n"
              "subprocess.Popen(['sh', '-c', 'sleep 600 & sleep 600'], start_new_session=True)\n"
              "stop_children()\n" % os.path.join(ROOT, "scripts"))
    env = {"PATH": "/usr/bin:/bin", "PLC_CELL_BENCH_MARK": marker}
    p = subprocess.Popen(["/usr/bin/python3", "-c", script], env=env, stdin=subprocess.DEVNULL,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)
    out = finish(p)
    assert p.returncode == 0, out
    left = marked(marker)
    assert left == [], "left behind:\n%s\n%s" % (described(left), out)
