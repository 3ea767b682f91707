"""`plc_cell run --watch-program` as a user runs it: the demo conveyor (its gate: the
scenario file and 20 s of exploration) served with the monitor, its program file saved anew
while it scans. A harmless change (the part counter's preset) goes live through the gate; a
change that breaks the interlock property is refused with the property's report and the
running program kept; a text that does not parse is refused at its line; each attempt is in
the audit trail with the file as its source, and the file is never rewritten by the cell."""
import json
import os
import shutil
import subprocess
import sys
import time
import urllib.error
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
from pyutil import ROOT, devel, free_port, stop  # noqa: E402

SRC = os.path.join(ROOT, "examples", "conveyor")
ORIGINAL = open(os.path.join(SRC, "conveyor.il")).read()
BROKEN = ORIGINAL.replace("OR      Y1\nANDLD", "OR      Y2\nANDLD")
HARMLESS = ORIGINAL.replace("CTR     C0 9999", "CTR     C0 5000")
UNPARSABLE = ORIGINAL.replace("CTR     C0 9999", "CTR     C0 9999 7", 1)
assert len({ORIGINAL, BROKEN, HARMLESS, UNPARSABLE}) == 4

LIMIT = 120  # s: a gate on the demo takes about a second; the suite loads the machine


def get(base, path):
    with urllib.request.urlopen(base + path, timeout=5) as r:
        return json.loads(r.read())


def until(what, probe, proc, log_path):
    """probe()'s first true answer within LIMIT, or a failure naming what was awaited."""
    deadline = time.monotonic() + LIMIT
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise AssertionError("plc_cell run ended (%s) while waiting for %s:\n%s"
                                 % (proc.returncode, what, open(log_path).read()[-3000:]))
        try:
            answer = probe()
        except (urllib.error.URLError, ConnectionError):
            answer = None
        if answer:
            return answer
        time.sleep(0.1)
    raise AssertionError("no %s within %d s:\n%s" % (what, LIMIT, open(log_path).read()[-3000:]))


def save(path, text):
    """As an editor saves: a new file renamed over the old one."""
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def test_a_saved_program_goes_live_only_through_the_gate(tmp_path):
    folder = str(tmp_path)
    for f in ("conveyor.il", "conveyor.scenario.yaml"):
        shutil.copy(os.path.join(SRC, f), folder)
    http = free_port()
    config = os.path.join(folder, "conveyor.yaml")
    with open(config, "w") as f:
        f.write(open(os.path.join(SRC, "conveyor.yaml")).read()
                + "servers:\n  http:\n    tcp: 127.0.0.1:%d\n" % http)
    program = os.path.join(folder, "conveyor.il")
    log_path = os.path.join(folder, "run.log")
    base = "http://127.0.0.1:%d" % http
    tool = os.path.join(devel(), "lib", "plc_cell", "plc_cell")
    with open(log_path, "w") as log:
        proc = subprocess.Popen([tool, "run", "--config", config, "--watch-program"], cwd=folder,
                                stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                start_new_session=True)
    try:
        first = until("the monitor's program", lambda: get(base, "/api/edit"), proc, log_path)
        assert first["text"] == ORIGINAL
        assert "watching " + program in open(log_path).read()

        def entries(n):
            log = get(base, "/api/edit/log?last=50")
            items = log if isinstance(log, list) else log.get("entries", [])
            return items if len(items) >= n else None

        save(program, HARMLESS)
        applied = until("an entry for the harmless change", lambda: entries(1), proc, log_path)[-1]
        assert applied["source"] == "file", applied
        assert applied["result"] == "applied", applied
        assert applied["gate"]["passed"] is True, applied
        live = get(base, "/api/edit")
        assert live["text"] == HARMLESS and live["hash"] != first["hash"]

        save(program, BROKEN)
        refused = until("an entry for the broken change", lambda: entries(2), proc, log_path)[-1]
        assert refused["source"] == "file" and refused["result"] == "refused", refused
        assert refused["gate"]["passed"] is False, refused
        assert "property always: pick_request -> not conveyor_run violated" in json.dumps(refused["gate"]), \
            refused["gate"]
        assert get(base, "/api/edit")["text"] == HARMLESS, "a refused change leaves the running program"

        save(program, UNPARSABLE)
        bad = until("an entry for the text that does not parse", lambda: entries(3), proc, log_path)[-1]
        assert bad["result"] == "refused", bad
        line = ORIGINAL[:ORIGINAL.index("CTR     C0 9999")].count("\n") + 1
        assert any(e["line"] == line for e in bad.get("errors", [])), bad
        assert get(base, "/api/edit")["text"] == HARMLESS

        assert open(program).read() == UNPARSABLE, "a change from the file is the file: never rewritten"
        out = open(log_path).read()
        assert out.count("program change applied") == 1, out
        assert out.count("program change refused") == 2, out
    finally:
        stop(proc)
