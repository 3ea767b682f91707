"""One monitor for a line of cells (`plc_cell run --line examples/line/line.line.yaml
--http-tcp`): the overview lists every cell with its true RUN/STOP (a cell stopped through
its API shows STOP, the others RUN), a wire's values follow its source, one click opens a
cell's ladder page, and a cell's watch table reads a qualified name of another cell. Also
the overview of a line's recording (`plc_cell monitor --recording`), one cursor for all.
With --properties FILE, the overview shows each property of the file and the last one
violated, live (a violation the test forces) and at a recording's cursor."""
import json
import os
import subprocess
import urllib.error
import urllib.request

import pytest

from conftest import ROOT, get_json, js, run, shell, wait, wait_for_server
from pyutil import free_port, stop
from test_monitor_page import watch_add, watch_value

LINE = os.path.join(ROOT, "examples", "line", "line.line.yaml")
CELLS = ["infeed", "robot", "test"]


def serve(scratch, name, cmd):
    """cmd with --http-tcp on a free port added, once its monitor answers: (process, base, session)."""
    http = free_port()
    log_path = os.path.join(scratch, name + ".log")
    with open(log_path, "w") as log:
        proc = shell("%s --http-tcp 127.0.0.1:%d" % (cmd, http), stdout=log, stderr=subprocess.STDOUT)
    base = "http://127.0.0.1:%d" % http
    try:
        return proc, base, wait_for_server(base, proc, log_path)
    except BaseException:
        stop(proc)
        raise


@pytest.fixture(scope="module")
def line(scratch):
    proc, base, session = serve(scratch, "run_line", "plc_cell run --line %s --http-writable all" % LINE)
    try:
        yield {"base": base, "token": session["token"]}
    finally:
        stop(proc)


def post(line, path, body):
    req = urllib.request.Request(line["base"] + path, data=json.dumps(body).encode(), method="POST",
                                 headers={"Content-Type": "application/json", "X-Plc-Token": line["token"]})
    with urllib.request.urlopen(req, timeout=5) as r:
        return json.loads(r.read().decode())


def cell_text(driver, cell, column):
    return js(driver, "const td = document.querySelector(`#cells tr[data-cell='${arguments[0]}'] td.${arguments[1]}`);"
                      "return td ? td.textContent : null", cell, column)


def wire_row(driver, source):
    """The overview's row of the wire from source: {from, to} as shown."""
    return js(driver, "const tr = [...document.querySelectorAll('#wires tr[data-wire]')]"
                      ".find(r => r.querySelector('td.from').textContent === arguments[0]);"
                      "return tr ? {from: tr.querySelector('td.from-value').textContent,"
                      "             to: tr.querySelector('td.to-value').textContent} : null", source)


def open_overview(driver, base):
    driver.get(base + "/")
    wait(driver, "every cell in the overview", lambda d: all(cell_text(d, c, "mode") for c in CELLS))


def test_every_cell_is_listed_with_its_true_run_stop(line, browser):
    open_overview(browser, line["base"])
    wait(browser, "every cell in RUN", lambda d: [cell_text(d, c, "mode") for c in CELLS] == ["RUN"] * 3)
    assert post(line, "/cell/robot/api/mode", {"mode": "stop"}) == {"ok": True}
    try:
        wait(browser, "robot in STOP, the others in RUN",
             lambda d: [cell_text(d, c, "mode") for c in CELLS] == ["RUN", "STOP", "RUN"])
        # What the cell's own page says: the overview tells the same.
        assert get_json(line["base"] + "/cell/robot/api/status")["mode"] == "stop"
    finally:
        post(line, "/cell/robot/api/mode", {"mode": "run"})
    wait(browser, "robot in RUN again", lambda d: cell_text(d, "robot", "mode") == "RUN")
    assert "no properties watched" in browser.find_element("id", "properties").text


def test_a_wire_follows_its_source(line, browser):
    open_overview(browser, line["base"])
    before = get_json(line["base"] + "/cell/robot/api/read?a=ready")["values"]["ready"]
    held = 1 - before
    post(line, "/cell/robot/api/force", {"address": "ready", "action": "on" if held else "off"})
    try:
        # robot.ready -> infeed.robot_ready has no delay: both ends show the forced value.
        wait(browser, "the wire robot.ready at %d on both ends" % held,
             lambda d: wire_row(d, "robot.ready") == {"from": str(held), "to": str(held)})
        assert get_json(line["base"] + "/cell/infeed/api/read?a=robot_ready")["values"]["robot_ready"] == held
    finally:
        post(line, "/cell/robot/api/force", {"address": "ready", "action": "release"})


def test_one_click_opens_a_cells_ladder(line, browser):
    open_overview(browser, line["base"])
    link = browser.find_element("css selector", "#cells tr[data-cell='test'] a.cell-link")
    # The overview redraws at every poll; the link the user points at is still the one clicked.
    clock = cell_text(browser, "test", "clock")
    wait(browser, "the overview redrawn with a later clock", lambda d: cell_text(d, "test", "clock") != clock)
    link.click()
    wait(browser, "the test cell's page", lambda d: d.current_url == line["base"] + "/cell/test/")
    wait(browser, "its ladder's networks", lambda d: d.find_elements("css selector", "#ladder .net"))
    wait(browser, "the page naming cell test", lambda d: d.find_element("id", "source").text.startswith("cell test"))
    # The test station's own signal names are drawn, not another cell's.
    assert js(browser, "return document.querySelector('#ladder').textContent.includes('robot_request')")
    assert browser.find_element("id", "overview-link").is_displayed()


def test_a_watch_reads_a_qualified_name_of_another_cell(line, browser):
    browser.get(line["base"] + "/cell/infeed/")
    wait(browser, "the infeed's ladder", lambda d: d.find_elements("css selector", "#ladder .net"))
    watch_add(browser, "robot.ready")
    before = get_json(line["base"] + "/cell/robot/api/read?a=ready")["values"]["ready"]
    wait(browser, "robot.ready's value in the infeed's watch table",
         lambda d: watch_value(d, "robot.ready") == str(before))
    held = 1 - before
    post(line, "/cell/robot/api/force", {"address": "ready", "action": "on" if held else "off"})
    try:
        wait(browser, "robot.ready forced to %d seen from the infeed's page" % held,
             lambda d: (watch_value(d, "robot.ready") or "").startswith(str(held)))
    finally:
        post(line, "/cell/robot/api/force", {"address": "ready", "action": "release"})


def test_the_overview_of_a_line_that_is_gone_is_marked_stale(scratch, browser):
    proc, base, _ = serve(scratch, "run_line_gone", "plc_cell run --line %s" % LINE)
    try:
        open_overview(browser, base)
        wait(browser, "every cell in RUN", lambda d: [cell_text(d, c, "mode") for c in CELLS] == ["RUN"] * 3)
        assert not js(browser, "return document.body.classList.contains('stale')")
    finally:
        stop(proc)
    # The last values stay, each marked stale, and the banner says why and how old they are.
    banner = browser.find_element("id", "banner")
    wait(browser, "the banner saying the monitor does not answer",
         lambda d: banner.is_displayed() and "does not answer" in banner.text and " s old" in banner.text)
    assert js(browser, "return document.body.classList.contains('stale')")
    assert js(browser, "return getComputedStyle(document.querySelector(\"#cells td.mode\"), '::after').content") \
        == '" (stale)"'


def test_a_lines_recording_is_one_overview_on_one_cursor(scratch):
    path = os.path.join(scratch, "line.plcrec")
    code, out = run("plc_cell sim --line %s --duration 4s --record %s" % (LINE, path))
    assert code == 0 and os.path.exists(path), out
    proc, base, session = serve(scratch, "monitor_line", "plc_cell monitor --recording %s" % path)
    try:
        assert session["cells"] == CELLS and session["kind"] == "replay"
        req = urllib.request.Request(base + "/cell/robot/api/replay", data=json.dumps({"seek_us": 2500000}).encode(),
                                     method="POST", headers={"X-Plc-Token": session["token"]})
        urllib.request.urlopen(req, timeout=5).read()
        o = get_json(base + "/api/overview")
        assert [c["name"] for c in o["cells"]] == CELLS
        # Every cell at the instant the robot's cursor moved to (the last scan at or before it).
        for c in o["cells"]:
            assert 2400000 <= c["t_us"] <= 2500000, (c["name"], c["t_us"])
            assert c["mode"] == "run"
        assert len(o["wires"]) == 8 and all(w["error"] == "" for w in o["wires"]), o["wires"]
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(base + "/cell/nope/api/status", timeout=5)
        assert e.value.code == 404 and "no cell 'nope'" in json.loads(e.value.read().decode())["error"]
    finally:
        stop(proc)


ZONE = "never: robot.in_zone and test.handler_in_zone"


def properties_file(scratch, name, properties, line=LINE):
    """A line's scenario file in scratch with these properties (and one case, as a scenario has)."""
    path = os.path.join(scratch, name + ".scenario.yaml")
    with open(path, "w") as f:
        f.write("line: %s\nproperties:\n%s\ncases:\n  - name: a\n    steps:\n      - after: 1ms\n"
                % (line, "".join("  - %s\n" % p for p in properties)))
    return path


def property_row(driver, i):
    """The overview's row of property i: {text, state, violations, last} as shown."""
    return js(driver, "const tr = document.querySelector(`#property-table tr[data-property='${arguments[0]}']`);"
                      "return tr ? {text: tr.querySelector('td.text').textContent,"
                      "             state: tr.querySelector('td.state').textContent,"
                      "             violations: tr.querySelector('td.violations').textContent,"
                      "             last: tr.querySelector('td.last').textContent} : null", i)


def test_a_forced_violation_shows_as_the_last_property_violated(scratch, browser):
    path = properties_file(scratch, "zone", ["never: robot.in_zone and test.handler_in_zone"])
    proc, base, session = serve(scratch, "run_line_properties",
                                "plc_cell run --line %s --http-writable all --properties %s" % (LINE, path))
    live = {"base": base, "token": session["token"]}
    try:
        open_overview(browser, base)
        wait(browser, "the property holding, never violated",
             lambda d: property_row(d, 0) == {"text": ZONE, "state": "holding", "violations": "0", "last": "–"})
        assert not browser.find_element("id", "last-violated").is_displayed()
        assert "1 property of %s" % path in browser.find_element("id", "properties").text
        post(live, "/cell/robot/api/force", {"address": "in_zone", "action": "on"})
        post(live, "/cell/test/api/force", {"address": "handler_in_zone", "action": "on"})
        try:
            banner = browser.find_element("id", "last-violated")
            wait(browser, "the last violated on top, going on",
                 lambda d: banner.is_displayed() and banner.text.startswith("last violated: " + ZONE + " at ")
                 and "so far" in banner.text and "robot.in_zone = ON, test.handler_in_zone = ON" in banner.text)
            row = property_row(browser, 0)
            assert row["state"].startswith("violated since ") and row["violations"] == "1", row
            assert js(browser, "return getComputedStyle(document.getElementById('last-violated')).backgroundColor") \
                == "rgb(197, 48, 48)"  # the page's error red
        finally:
            post(live, "/cell/robot/api/force", {"address": "in_zone", "action": "release"})
            post(live, "/cell/test/api/force", {"address": "handler_in_zone", "action": "release"})
        # Released: the property holds again, its violation ended with its length.
        wait(browser, "the property holding again after one violation",
             lambda d: (property_row(d, 0) or {}).get("state") == "holding")
        o = get_json(base + "/api/overview")
        assert o["properties"][0]["violations"] == 1 and o["last_violated"]["ongoing"] is False, o
        assert o["last_violated"]["duration_us"] > 0
        assert "so far" not in browser.find_element("id", "last-violated").text
    finally:
        stop(proc)


def test_a_lines_recording_tells_its_properties_at_the_cursor(scratch):
    """The example line's robot is in the shared zone from 3.54 s to 4.84 s (its scenario's
    cases): `never: robot.in_zone` is violated there, and nowhere else in 6 s."""
    rec = os.path.join(scratch, "line6.plcrec")
    code, out = run("plc_cell sim --line %s --duration 6s --record %s" % (LINE, rec))
    assert code == 0, out
    path = properties_file(scratch, "robot_zone", ["never: robot.in_zone", "always: infeed.R0 >= 0"])
    proc, base, session = serve(scratch, "monitor_line_properties",
                                "plc_cell monitor --recording %s --properties %s" % (rec, path))
    try:
        def at(t_us):
            req = urllib.request.Request(base + "/cell/robot/api/replay", data=json.dumps({"seek_us": t_us}).encode(),
                                         method="POST", headers={"X-Plc-Token": session["token"]})
            urllib.request.urlopen(req, timeout=5).read()
            return get_json(base + "/api/overview")
        o = at(1000000)
        assert o["properties_t_us"] == 1000000
        assert [p["state"] for p in o["properties"]] == ["holding", "holding"] and o["last_violated"] is None, o
        o = at(3600000)
        zone = o["properties"][0]
        assert zone["state"] == "violated" and zone["since_us"] == 3540000 and zone["violations"] == 1, zone
        assert o["last_violated"] == {"text": "never: robot.in_zone", "where": path + ":3", "begin_us": 3540000,
                                      "duration_us": 60000, "ongoing": True,
                                      "values": [{"name": "robot.in_zone", "value": "ON"}]}, o["last_violated"]
        o = at(5500000)
        assert o["properties"][0]["state"] == "holding" and o["properties"][1]["violations"] == 0
        assert o["last_violated"]["duration_us"] == 1300000 and o["last_violated"]["ongoing"] is False
        o = at(0)  # back before it: no violation yet
        assert o["properties"][0]["violations"] == 0 and o["last_violated"] is None
    finally:
        stop(proc)


def test_properties_of_another_line_or_a_cell_are_refused_where_they_say_so(scratch):
    rec = os.path.join(scratch, "line1.plcrec")
    assert run("plc_cell sim --line %s --duration 100ms --record %s" % (LINE, rec))[0] == 0
    other = properties_file(scratch, "other", ["never: robot.in_zone"],
                            os.path.join(ROOT, "examples", "line", "line_broken.line.yaml"))
    code, out = run("plc_cell monitor --recording %s --properties %s --duration 1s" % (rec, other))
    assert code == 1 and "%s:1:7: error: --properties: line: " % other in out and "is not line example_line" in out, out
    code, out = run("plc_cell run --line %s --properties %s --duration 1s" % (LINE, other))
    assert code == 1 and "%s:1:7: error:" % other in out and "is not the line run" in out, out
    unknown = properties_file(scratch, "unknown", ["never: robot.no_such_signal", "never: robot.counter.belt"])
    code, out = run("plc_cell run --line %s --properties %s --duration 1s" % (LINE, unknown))
    assert code == 1 and "%s:3: error: property 'never: robot.no_such_signal'" % unknown in out, out
    assert "%s:4: error: property 'never: robot.counter.belt': " % unknown in out and "addresses and signals" in out, out
