"""Processes a script started, and everything they started in turn, stopped on every way out.

The test runner, the benchmarks and the tests start servers, masters and nodelet managers.
Each is started in a session of its own (its process group), and stopped through its id:
never by a name pattern, which would also stop a neighbour's build or test. A child that
left its parent's group (roslaunch's nodes, a server started with setsid) is still found
through the parent links in /proc while its parent lives, so the whole tree is collected
first and then stopped."""
import os
import signal
import subprocess
import time


def _parents():
    """pid -> parent pid of every process now."""
    out = {}
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open("/proc/%s/stat" % d) as f:
                stat = f.read()
        except OSError:
            continue
        # The name is in parentheses and may hold spaces; the parent follows the state.
        out[int(d)] = int(stat[stat.rfind(")") + 2:].split()[1])
    return out


def descendants(pid):
    """Every process below pid (children, their children, ...), found by parent links."""
    parents = _parents()
    children = {}
    for p, pp in parents.items():
        children.setdefault(pp, []).append(p)
    out, todo = [], [pid]
    while todo:
        for c in children.get(todo.pop(), []):
            out.append(c)
            todo.append(c)
    return out


def _signal(pids, sig):
    for p in pids:
        try:
            os.kill(p, sig)
        except (ProcessLookupError, PermissionError):
            pass


def signal_tree(pid, sig):
    """sig to pid's process group, to pid and to every descendant (in whatever group)."""
    tree = [pid] + descendants(pid)
    try:
        os.killpg(pid, sig)
    except (ProcessLookupError, PermissionError):
        pass
    _signal(tree, sig)
    return tree


def stop(proc, grace=10.0, first=signal.SIGINT):
    """Stops proc (a Popen started with start_new_session=True) and its tree: `first` (a
    user's Ctrl-C: servers save and close) for up to grace seconds, then SIGKILL to whatever
    of the tree is left. Returns proc's exit status."""
    if proc.poll() is not None:  # what it left in its group goes with it (the group's id
        try:                      # is not reused while a member lives)
            os.killpg(proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        return proc.returncode
    tree = signal_tree(proc.pid, first)
    try:
        proc.wait(timeout=grace)
    except subprocess.TimeoutExpired:
        pass
    # The tree as collected before the parent went (its orphans are no longer below it).
    tree = set(tree) | set(descendants(proc.pid))
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    _signal(tree, signal.SIGKILL)
    try:
        return proc.wait(timeout=10)
    except subprocess.TimeoutExpired:  # a process in uninterruptible sleep: say so, go on
        return None


def stop_children(grace=10.0):
    """Stops every child of this process that is still alive, and its tree, as stop() does:
    the last word of a script that starts processes. A SIGTERM turned into SystemExit between
    a child's fork and the bookkeeping of the one who started it (Started, entered into an
    ExitStack) would otherwise leave that child running: it is still this process's child."""
    me = os.getpid()
    children = [pid for pid, parent in _parents().items() if parent == me]
    trees = {pid: signal_tree(pid, signal.SIGINT) for pid in children}
    deadline = time.monotonic() + grace
    while time.monotonic() < deadline and any(_alive(pid) for pid in children):
        time.sleep(0.05)  # polling the children's end, bounded by grace
    for pid, tree in trees.items():
        try:
            os.killpg(pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        _signal(set(tree) | set(descendants(pid)), signal.SIGKILL)
    for pid in children:
        try:
            os.waitpid(pid, 0)
        except ChildProcessError:
            pass


def _alive(pid):
    """pid is this process's child and has not ended (reaping it if it has)."""
    try:
        return os.waitpid(pid, os.WNOHANG) == (0, 0)
    except ChildProcessError:
        return False


class Started:
    """`with Started([...]) as p:` runs a command in a session of its own and stops it (and
    what it started) when the block ends, by an exception, Ctrl-C or SIGTERM included: a
    SIGTERM to the script is turned into SystemExit so that the block's exit runs."""

    def __init__(self, argv, grace=10.0, **popen_kw):
        popen_kw.setdefault("stdin", subprocess.DEVNULL)
        self.proc = subprocess.Popen(argv, start_new_session=True, **popen_kw)
        self.grace = grace
        exit_on_sigterm()

    def __enter__(self):
        return self.proc

    def __exit__(self, *exc):
        stop(self.proc, self.grace)
        return False


def exit_on_sigterm():
    if signal.getsignal(signal.SIGTERM) in (signal.SIG_DFL, None):
        def on_term(signum, frame):
            raise SystemExit(128 + signum)
        signal.signal(signal.SIGTERM, on_term)


def become_subreaper():
    """Makes this process the parent of every orphan below it (prctl PR_SET_CHILD_SUBREAPER),
    so that what a child left behind in another session can still be found and stopped
    (orphans())."""
    import ctypes
    libc = ctypes.CDLL(None, use_errno=True)
    return libc.prctl(36, 1, 0, 0, 0) == 0


def orphans(known):
    """This process's children that are not in `known` (pids of what it started itself):
    after become_subreaper(), what its children's children left behind. Each is stopped with
    its own tree and reaped; returns [(pid, command line)]."""
    me = os.getpid()
    out = []
    for pid, parent in _parents().items():
        if parent != me or pid in known:
            continue
        try:
            with open("/proc/%d/cmdline" % pid, "rb") as f:
                cmd = f.read().replace(b"\0", b" ").decode(errors="replace").strip()
        except OSError:
            cmd = "?"
        _signal([pid] + descendants(pid), signal.SIGKILL)
        try:
            os.waitpid(pid, 0)
        except ChildProcessError:
            pass
        out.append((pid, cmd or "(ended)"))
    return out


def wait_until(predicate, limit, what, proc=None, step=0.05):
    """Polls predicate() until it is true, within limit seconds; past it, or when proc has
    ended first, raises RuntimeError naming what was waited for."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        if proc is not None and proc.poll() is not None:
            raise RuntimeError("%s: the process ended (status %s) first" % (what, proc.returncode))
        time.sleep(step)
    raise RuntimeError("no %s after %.0f s" % (what, limit))
