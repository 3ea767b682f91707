"""Every command in README.md and docs/ works when pasted.

The docs mark their blocks: ```sh holds commands a user pastes, ```console a transcript
(`$ command` lines, then the output the command prints), ```text or a language name
(yaml, il) anything else. This test runs every sh and console block, in order, from the
repository's root (files the commands write there are removed afterwards), in a shell that has sourced
.build/ws/devel/setup.bash (as the README says), against the demo cell
(launch/cell_sim.launch) on a private ROS master port. A console block's output lines
must appear in the command's output in the same order (`...` stands for any lines); a
transcript that shows a command's error output documents a failure, so its exit status is
free, but its lines must match.

A command that streams (rostopic echo, roslaunch, plc_cell run without --duration, ...)
passes when it prints something and no error within its window; every other command must
exit 0. A command ending in `&` runs in the background, as in a user's shell, until the
block's `kill %N` or the block's end; the next command starts once it has printed its first
line (a server announces its ports). An unmarked block that looks like commands fails the test: it must say which it is."""
import glob
import os
import re
import select
import shlex
import subprocess
import sys
import tempfile
import time

import pytest

# realpath: run from the workspace, this file is reached through its links to the package.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
from pyutil import ROOT, devel, free_port, stop  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from ros_loopback import loopback_env  # noqa: E402

DOCS = ["README.md"] + sorted(os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "docs", "*.md")))

FENCE = re.compile(r"^```([^\n]*)\n(.*?)^```\s*$", re.M | re.S)
SHELLISH = re.compile(r"^\s*(\$ |source |rostopic |rosservice |roslaunch |rosrun |rostest |plc_cell |make |mbpoll |"
                      r"\.build/ws/devel/lib/)")
STREAMING = re.compile(r"^(rostopic (echo|hz)|roslaunch |rosbag record(?!.*--duration)|rosrun plc_cell plc_node|make demo|"
                       r"plc_cell run (?!.*--duration))")
ERRORS = re.compile(r"Traceback|ERROR|Cannot load message|Unable to load type|command not found|"
                    r"No such file|process has died|error:", re.I)
COMMAND_LIMIT = 300.0
GRACE = 1.0  # s: a streaming command keeps running this long after it is up, to show an error
# What a streaming command (STREAMING) prints once it works: it is stopped GRACE seconds later.
UP = [(re.compile(r"^make demo LINE="), re.compile(r"serving monitor http")),
      (re.compile(r"^(make demo|roslaunch )"), re.compile(r"process\[plc_node[^\]]*\]: started with pid")),
      (re.compile(r"^rostopic echo"), re.compile(r"^---$", re.M)),
      (re.compile(r"^rostopic hz"), re.compile(r"average rate")),
      (re.compile(r"^rosbag record"), re.compile(r"Recording to")),
      (re.compile(r"^rosrun plc_cell plc_node"), re.compile(r"plc_node: cell ")),
      (re.compile(r"^plc_cell run"), re.compile(r"scanning every"))]
# `make test` is the command that runs this test; it is not run again from inside itself.
SELF = {"make test"}


def blocks(path):
    text = open(os.path.join(ROOT, path), encoding="utf-8").read()
    for m in FENCE.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        yield line, m.group(1).strip(), m.group(2)


def commands(kind, body):
    """(command, expected output lines) of a sh or console block; continuations joined."""
    out = []
    lines = body.split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        if kind == "console" and not line.startswith("$ "):
            if out:
                out[-1][1].append(line)
            i += 1
            continue
        cmd = line[2:] if kind == "console" else line
        while cmd.endswith("\\") and i + 1 < len(lines):
            i += 1
            cmd = cmd[:-1] + " " + lines[i].strip()
        i += 1
        stripped = cmd.split(" #")[0].strip() if not cmd.strip().startswith("#") else ""
        if stripped:
            out.append((stripped, []))
    return [(c, [e for e in exp if e.strip()]) for c, exp in out]


class Shell:
    """A user's shell: the scratch folder, setup.bash sourced, a private ROS master."""

    def __init__(self, workdir, master_port):
        self.workdir, home = workdir
        # On loopback: no doc command depends on the machine's hostname resolving.
        self.env = loopback_env(dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % master_port,
                                     ROS_HOME=home, PYTHONUNBUFFERED="1"))
        self.env.pop("ROS_NAMESPACE", None)

    def start(self, cmd, log=None):
        """cmd running; its output on a pipe, or in the file log (a process that runs the
        whole page and is never read must not fill a pipe and stall)."""
        script = "source %s/setup.bash >/dev/null 2>&1\n%s\n" % (shlex.quote(devel()), cmd)
        return subprocess.Popen(["bash", "-c", script], cwd=self.workdir, env=self.env, stdin=subprocess.DEVNULL,
                                stdout=log or subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)

    def run(self, cmd):
        """(exit code, output) of a command that ends by itself."""
        p = self.start(cmd)
        try:
            out, _ = p.communicate(timeout=COMMAND_LIMIT)
            return p.returncode, out.decode(errors="replace")
        except subprocess.TimeoutExpired:
            stop(p)
            out, _ = p.communicate()
            return -1, out.decode(errors="replace") + "\n[killed after %d s]" % COMMAND_LIMIT

    def stream(self, cmd):
        """(exit code, or None if it was still running when stopped; output; whether it came
        up) of a command that runs until stopped. It runs until it is up (its UP pattern in
        the output, within COMMAND_LIMIT: make demo may build first), then GRACE seconds
        more to show an error it makes at once."""
        up = next(ready for which, ready in UP if which.match(cmd))
        p = self.start(cmd)
        out, was_up = b"", False
        deadline = time.monotonic() + COMMAND_LIMIT
        try:
            while time.monotonic() < deadline and p.poll() is None:
                if select.select([p.stdout], [], [], 0.2)[0]:
                    out += os.read(p.stdout.fileno(), 65536)
                    if not was_up and up.search(out.decode(errors="replace")):
                        was_up = True
                        deadline = time.monotonic() + GRACE
        finally:
            code = p.poll()
            stop(p)
            rest, _ = p.communicate()
        return code, (out + rest).decode(errors="replace"), was_up


def untracked():
    """Files in the repository that git does not know (the build folders aside)."""
    out = subprocess.run(["git", "ls-files", "--others", "--exclude-standard", "-z"], cwd=ROOT,
                         stdout=subprocess.PIPE, check=False).stdout.decode()
    return {f for f in out.split("\0") if f}


@pytest.fixture(scope="module")
def workdir():
    # The repository itself, as a user would paste the commands there; what they write
    # (trace.csv, ...) is removed afterwards. A ROS_HOME of its own keeps logs out of it.
    before = untracked()
    home = tempfile.mkdtemp(prefix="plc_cell_docs.")
    yield ROOT, home
    for f in untracked() - before:
        os.remove(os.path.join(ROOT, f))
    subprocess.call(["rm", "-rf", home])


def wait_for_service(shell, name, limit=60.0):
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        code, out = shell.run("rosservice list")
        if code == 0 and name in out.split():
            return True
        time.sleep(0.5)  # polling the master for the demo to come up, not waiting for a result
    return False


def needs_cell(path):
    return any(re.search(r"\b(rostopic|rosservice|rosnode|rosparam)\b", body) and kind in ("sh", "console")
               for _, kind, body in blocks(path))


def test_every_command_block_is_marked():
    unmarked = []
    for path in DOCS:
        for line, kind, body in blocks(path):
            if kind == "" and any(SHELLISH.match(l) for l in body.split("\n")):
                unmarked.append("%s:%d" % (path, line))
    assert not unmarked, ("blocks with commands but no sh/console/text mark (the doc test cannot tell whether "
                          "to run them): %s" % ", ".join(unmarked))


def test_there_are_commands_to_run():
    n = sum(len(commands(k, b)) for p in DOCS for _, k, b in blocks(p) if k in ("sh", "console"))
    assert n >= 20, "only %d runnable commands found in the docs" % n


def runs_something(path):
    """A page has a case of its own only if it has a command to run: a page with none would
    count as a test that passed having run nothing."""
    return any(cmd not in SELF for _, kind, body in blocks(path) if kind in ("sh", "console")
               for cmd, _ in commands(kind, body))


@pytest.mark.parametrize("path", [p for p in DOCS if runs_something(p)])
def test_commands_work_when_pasted(path, workdir):
    runnable = [(line, kind, body) for line, kind, body in blocks(path) if kind in ("sh", "console")]
    shell = Shell(workdir, free_port())
    cell = None
    failures = []
    try:
        if needs_cell(path):
            cell_log = os.path.join(shell.workdir, "cell_sim.log")
            with open(cell_log, "wb") as log:
                cell = shell.start("roslaunch -p %s plc_cell cell_sim.launch"
                                   % shell.env["ROS_MASTER_URI"].rsplit(":", 1)[1], log)
            if not wait_for_service(shell, "/plc_node/read"):
                with open(cell_log, "rb") as log:
                    pytest.fail("the demo cell did not come up in 60 s (exit %s); its roslaunch printed:\n%s"
                                % (cell.poll(), log.read().decode(errors="replace")[-4000:]))
        for line, kind, body in runnable:
            jobs = []
            for cmd, expected in commands(kind, body):
                if cmd in SELF:
                    continue
                where = "%s:%d: %s" % (path, line, cmd)
                if cmd.endswith("&"):
                    job = shell.start(cmd[:-1])
                    jobs.append((where, job))
                    if not first_line(job, 20.0):
                        failures.append("%s\n  printed nothing in 20 s (exit %s)" % (where, job.poll()))
                    elif job.poll() is not None:
                        failures.append("%s\n  stopped at once (exit %d):\n%s"
                                        % (where, job.returncode, indent(job.stdout.read().decode(errors="replace"))))
                    continue
                kill = re.match(r"^kill %(\d+)$", cmd)
                if kill:
                    n = int(kill.group(1))
                    if not 1 <= n <= len(jobs) or jobs[n - 1][1].poll() is not None:
                        failures.append("%s\n  job %d is not running: it stopped early" % (where, n))
                    else:
                        stop(jobs[n - 1][1])
                    continue
                streaming = STREAMING.match(cmd) is not None
                was_up = True
                if cmd.startswith("make demo"):  # its own master: it starts the demo cell itself
                    code, out, was_up = Shell(workdir, free_port()).stream(cmd)
                elif streaming:
                    code, out, was_up = shell.stream(cmd)
                else:
                    code, out = shell.run(cmd)
                if code is None and not was_up:  # stopped at the limit, never up
                    failures.append("%s\n  did not come up (no %r in its output):\n%s"
                                    % (where, next(u.pattern for w, u in UP if w.match(cmd)), indent(out)))
                elif code is None:
                    if ERRORS.search(out):
                        failures.append("%s\n  streamed an error:\n%s" % (where, indent(out)))
                elif code != 0 and not (kind == "console" and expected):
                    failures.append("%s\n  exit %d:\n%s" % (where, code, indent(out)))
                elif expected:
                    missing = unmatched(expected, out)
                    if missing:
                        failures.append("%s\n  output lacks %r; it was:\n%s" % (where, missing, indent(out)))
            for where, job in jobs:
                stop(job)
    finally:
        if cell is not None:
            stop(cell)
    assert not failures, "\n\n".join(failures)


def first_line(p, limit):
    """True once p has printed a line (it keeps running), False if it printed none in time."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        r, _, _ = select.select([p.stdout], [], [], max(0.0, deadline - time.monotonic()))
        if r:
            return bool(p.stdout.readline())
    return False


def unmatched(expected, out):
    """The first expected line not found in order in out (None if all are); '...' skips."""
    got = [l.rstrip() for l in out.split("\n")]
    pos = 0
    for e in expected:
        e = e.rstrip()
        if e.strip() == "...":
            continue
        while pos < len(got) and got[pos].strip() != e.strip():
            pos += 1
        if pos == len(got):
            return e
        pos += 1
    return None


def indent(text, n=40):
    lines = text.rstrip().split("\n")
    if len(lines) > n:
        lines = lines[:10] + ["..."] + lines[-(n - 11):]
    return "\n".join("    " + l for l in lines)


# Words that belong to the project's tracker and working notes, not to a user's manual.
INTERNAL = re.compile(r"\b[Ii]ssue\s+#?\d+|\.\./shared|\bspec\b\s*(§|\d)|\bthe spec\b|\bseed\s+0\d\d|"
                      r"[Ss]tatus of issue|\bbranch `")


def test_docs_speak_of_the_product_only():
    found = []
    for path in DOCS:
        for n, line in enumerate(open(os.path.join(ROOT, path), encoding="utf-8"), 1):
            m = INTERNAL.search(line)
            if m:
                found.append("%s:%d: %r" % (path, n, m.group(0)))
    assert not found, "internal references in user docs (cite the manual by chapter instead):\n" + "\n".join(found)
