#!/usr/bin/python3
"""CPU and memory per cell: N demo cells (examples/conveyor, 1 ms scan) as N plc_node
processes, then as N plc_cell/PlcNodelet in one nodelet manager (each its own scan thread,
then all on one shared scan thread, ~shared_scan), side by side in one run.

For each count and way, the cells are started on a master of their own (loopback, a free
port), left to settle, then measured over a window: CPU as the processes' user + system
time over the window's wall time (100 % = one core), RSS as VmRSS at the window's end,
threads from /proc, and overruns as each cell's "scan" entry on /diagnostics counts them
(its overruns at the window's end less those at its start), with the cells' average scan
time. The machine's load average is printed with each row: the other processes on the
machine share the cores, and a scan thread they preempt overruns; --rt-priority N runs the
scan threads under SCHED_FIFO (where allowed) so that only the cells themselves can. Each
overrun is split as the cells count it: "off the CPU" when the scan thread's own CPU time
since it woke does not explain it (woken late or preempted: the machine's), "from the
cells" when it does (the scans and after-scan work ran past the period).

    bench/many_cells.py --workspace .build/ws --cells 1,20,100 --seconds 10

prints a Markdown table (docs/performance.md, "Many cells")."""
import argparse
import contextlib
import os
import socket
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
sys.path.insert(0, os.path.join(HERE, "scripts"))
from process_tree import Started, stop_children, wait_until  # noqa: E402
from ros_loopback import loopback_env  # noqa: E402

TICKS = os.sysconf("SC_CLK_TCK")
SHARED_THREADS = {"shared": 1, "shared2": 2}  # way: ~shared_scan_threads


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def cpu_seconds(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / TICKS  # utime, stime


def status(pid, key):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    return 0


class Overruns:
    """Each cell's overruns, from the "scan" entries on /diagnostics."""

    def __init__(self):
        import rospy
        from diagnostic_msgs.msg import DiagnosticArray
        self.last = {}
        self.off_cpu = {}  # each cell's overruns with its scan thread off the CPU
        self.cycle = {}  # each cell's average scan time, us
        rospy.Subscriber("/diagnostics", DiagnosticArray, self.on_diag, queue_size=1000)

    def on_diag(self, msg):
        for st in msg.status:
            if st.name.endswith(": scan"):
                values = {kv.key: kv.value for kv in st.values}
                if "overruns" in values:
                    self.last[st.name] = int(values["overruns"])
                    self.off_cpu[st.name] = int(values["overruns, thread off the CPU"])
                    self.cycle[st.name] = float(values["cycle avg (us)"])


def workspace_env(ws):
    """The environment of a shell that sourced ws's devel space: the nodelet manager finds
    plc_cell/PlcNodelet through its ROS_PACKAGE_PATH, whatever the caller had sourced."""
    setup = os.path.join(ws, "devel", "setup.bash")
    if not os.path.exists(setup):
        raise SystemExit("%s: no devel space (no devel/setup.bash); build it with make build" % ws)
    out = subprocess.run(["bash", "-c", 'source "$0" >/dev/null && env -0', setup], stdout=subprocess.PIPE,
                         stdin=subprocess.DEVNULL, timeout=60, check=True).stdout
    return dict(kv.split("=", 1) for kv in out.decode().split("\0") if "=" in kv)


def start_nodes(stack, ws, cell, n, scan, prio, env, log):
    exe = os.path.join(ws, "devel/lib/plc_cell/plc_node")
    return [stack.enter_context(Started(
        [exe, "__name:=plc_node", "__ns:=/cell_%d" % i, "_cell:=" + cell, "_scan_period:=%g" % scan,
         "_rt_priority:=%d" % prio], env=env, stdout=subprocess.DEVNULL, stderr=log)) for i in range(n)]


def start_nodelets(stack, cell, n, scan, prio, env, log, shared=0):
    import rospy
    from nodelet.srv import NodeletLoad
    manager = stack.enter_context(Started(["/usr/lib/nodelet/nodelet", "manager", "__name:=cells"], env=env,
                                          stdout=subprocess.DEVNULL, stderr=log))
    rospy.wait_for_service("/cells/load_nodelet", timeout=30)
    load = rospy.ServiceProxy("/cells/load_nodelet", NodeletLoad)
    for i in range(n):
        name = "/cell_%d/plc_node" % i
        rospy.set_param(name + "/cell", cell)
        rospy.set_param(name + "/scan_period", scan)
        rospy.set_param(name + "/rt_priority", prio)
        rospy.set_param(name + "/shared_scan", shared > 0)
        rospy.set_param(name + "/shared_scan_threads", max(1, shared))
        why = "it answered no"
        try:
            loaded = load(name, "plc_cell/PlcNodelet", [], [], [], "").success
        except rospy.ServiceException as e:  # the nodelet threw while it loaded
            loaded, why = False, str(e)
        if not loaded:
            raise SystemExit("the manager did not load %s (%s); its log:\n%s" % (name, why, tail(log)))
    return [manager]


def tail(log, lines=20):
    log.flush()
    log.seek(0)
    return "".join(log.read().decode(errors="replace").splitlines(True)[-lines:])


def measure(way, ws, cell, n, scan, prio, settle, seconds, env, overruns):
    # Whatever was started stops when the window ends, or when anything fails on the way
    # (a cell that does not load, Ctrl-C, SIGTERM): nothing is left running.
    with contextlib.ExitStack() as stack:
        log = stack.enter_context(tempfile.TemporaryFile())
        stack.callback(overruns.last.clear)
        stack.callback(overruns.off_cpu.clear)
        stack.callback(time.sleep, 2)  # after the stop: the last /diagnostics of the stopped cells
        if way == "nodes":
            measured = start_nodes(stack, ws, cell, n, scan, prio, env, log)
        else:
            measured = start_nodelets(stack, cell, n, scan, prio, env, log, shared=SHARED_THREADS.get(way, 0))
        try:
            wait_until(lambda: len(overruns.last) >= n, 60 + n, "%s: all %d cells on /diagnostics" % (way, n))
        except RuntimeError as e:
            raise SystemExit("%s (%d are); the cells' log:\n%s" % (e, len(overruns.last), tail(log)))
        time.sleep(settle)
        before, before_off = dict(overruns.last), dict(overruns.off_cpu)
        cpu0, t0 = sum(cpu_seconds(p.pid) for p in measured), time.time()
        time.sleep(seconds)
        cpu1, t1 = sum(cpu_seconds(p.pid) for p in measured), time.time()
        after, after_off = dict(overruns.last), dict(overruns.off_cpu)
        rss = sum(status(p.pid, "VmRSS") for p in measured)
        threads = sum(status(p.pid, "Threads") for p in measured)
        cpu = 100.0 * (cpu1 - cpu0) / (t1 - t0)
        over = sum(after[k] - before.get(k, after[k]) for k in after)
        off = sum(after_off[k] - before_off.get(k, after_off[k]) for k in after_off)
        cycle = sum(overruns.cycle.values()) / max(1, len(overruns.cycle))
        return {"cpu": cpu, "rss_kb": rss, "threads": threads, "overruns": over, "off_cpu": off, "load": os.getloadavg()[0],
                "cycle": cycle}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--workspace", default=os.path.join(HERE, ".build/ws"))
    ap.add_argument("--cells", default="1,20,100", help="comma-separated counts")
    ap.add_argument("--ways", default="nodes,nodelets,shared",
                    help="nodes: a process per cell; nodelets: one manager, a scan thread per cell; "
                         "shared: one manager, one scan thread (~shared_scan); "
                         "shared2: the same over two scan threads (~shared_scan_threads: 2)")
    ap.add_argument("--scan", type=float, default=0.001, help="scan period, s")
    ap.add_argument("--rt-priority", type=int, default=0,
                    help="the scan threads' SCHED_FIFO priority (~rt_priority; 0: the normal scheduler)")
    ap.add_argument("--settle", type=float, default=5, help="s after the last cell is up")
    ap.add_argument("--seconds", type=float, default=10, help="s of the measuring window")
    ap.add_argument("--cell", default=os.path.join(HERE, "examples/conveyor/conveyor.yaml"))
    a = ap.parse_args()
    a.workspace = os.path.abspath(a.workspace)
    port = free_port()
    env = loopback_env(workspace_env(a.workspace))
    env["ROS_MASTER_URI"] = "http://localhost:%d" % port
    os.environ.update(env)
    with Started(["rosmaster", "--core", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                 stderr=subprocess.DEVNULL) as master:
        import rospy
        wait_until(lambda: master_up(port), 30, "ROS master on port %d" % port, master)
        rospy.init_node("many_cells_bench", anonymous=True, disable_signals=True)
        overruns = Overruns()
        print("| cells | way | CPU per cell (%% of a core) | RSS per cell (MB) | threads | scan (us) "
              "| overruns in %g s | of them off the CPU | from the cells | load |" % a.seconds)
        print("|---|---|---|---|---|---|---|---|---|---|")
        for n in [int(x) for x in a.cells.split(",")]:
            for way in a.ways.split(","):
                r = measure(way, a.workspace, a.cell, n, a.scan, a.rt_priority, a.settle, a.seconds, env, overruns)
                print("| %d | %s | %.2f | %.1f | %d | %.1f | %d | %d | %d | %.1f |" % (
                    n, way, r["cpu"] / n, r["rss_kb"] / 1024.0 / n, r["threads"], r["cycle"], r["overruns"],
                    r["off_cpu"], r["overruns"] - r["off_cpu"], r["load"]), flush=True)


def master_up(port):
    with socket.socket() as s:
        return s.connect_ex(("127.0.0.1", port)) == 0


if __name__ == "__main__":
    try:
        main()
    finally:
        stop_children()  # one a SIGTERM caught between its start and its bookkeeping
