"""One monitor for the cells of a process (`roslaunch plc_cell many_cells.launch cells:=2
monitor:=HOST:PORT`): each plc_node nodelet lists its cell in the process's directory and
the monitor nodelet serves them all; the overview lists each with its true RUN/STOP, one
click opens its ladder, and a nodelet unloaded leaves the overview."""
import json
import os
import subprocess
import time
import urllib.error
import urllib.request

import pytest

from conftest import WAIT, get_json, ros_env, run, shell, wait, wait_for_server
from pyutil import free_port, stop
from test_monitor_line import cell_text

CELLS = ["cell_0", "cell_1"]


def poll(what, condition, limit=WAIT):
    """condition() true within limit (the server may be starting again: no answer is false)."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        try:
            if condition():
                return
        except (urllib.error.URLError, ConnectionError, OSError, ValueError):
            pass
        time.sleep(0.2)  # polling the monitor, not waiting for a result
    pytest.fail("waited %.0f s for %s" % (limit, what))


@pytest.fixture(scope="module")
def manager(scratch):
    master, http = free_port(), free_port()
    env = ros_env(master)
    log_path = os.path.join(scratch, "many_cells.log")
    with open(log_path, "w") as log:
        proc = shell("roslaunch -p %d plc_cell many_cells.launch cells:=2 monitor:=127.0.0.1:%d monitor_writable:=all"
                     % (master, http), env, stdout=log, stderr=subprocess.STDOUT)
    try:
        base = "http://127.0.0.1:%d" % http
        wait_for_server(base, proc, log_path)
        # The monitor starts again as each cell comes: until both are there.
        poll("both cells in the monitor", lambda: get_json(base + "/api/session").get("cells") == CELLS)
        yield {"base": base, "env": env}
    finally:
        stop(proc)


def post(base, path, body):
    token = get_json(base + "/api/session")["token"]
    req = urllib.request.Request(base + path, data=json.dumps(body).encode(), method="POST",
                                 headers={"Content-Type": "application/json", "X-Plc-Token": token})
    with urllib.request.urlopen(req, timeout=5) as r:
        return json.loads(r.read().decode())


def test_the_overview_lists_each_nodelets_cell_with_its_true_mode(manager, browser):
    base = manager["base"]
    browser.get(base + "/")
    wait(browser, "both cells in RUN", lambda d: [cell_text(d, c, "mode") for c in CELLS] == ["RUN", "RUN"])
    assert post(base, "/cell/cell_1/api/mode", {"mode": "stop"}) == {"ok": True}
    try:
        wait(browser, "cell_1 in STOP, cell_0 in RUN", lambda d: [cell_text(d, c, "mode") for c in CELLS] == ["RUN", "STOP"])
        # The cell the monitor stopped is the nodelet's own: its ~read says so too.
        code, out = run("rosservice call /cell_1/plc_node/read M1924 1", manager["env"])
        assert code == 0, out
    finally:
        post(base, "/cell/cell_1/api/mode", {"mode": "run"})
    browser.find_element("css selector", "#cells tr[data-cell='cell_0'] a.cell-link").click()
    wait(browser, "cell_0's ladder", lambda d: d.current_url == base + "/cell/cell_0/" and
         d.find_elements("css selector", "#ladder .net"))


def test_a_nodelet_unloaded_leaves_the_overview(manager, browser):
    base = manager["base"]
    code, out = run("rosrun nodelet nodelet unload /cell_1/plc_node /cells", manager["env"])
    assert code == 0, out
    poll("the monitor with cell_0 alone", lambda: get_json(base + "/api/session").get("cells") == ["cell_0"])
    browser.get(base + "/")
    wait(browser, "cell_0 alone on the overview", lambda d: cell_text(d, "cell_0", "mode") == "RUN" and
         cell_text(d, "cell_1", "mode") is None)
