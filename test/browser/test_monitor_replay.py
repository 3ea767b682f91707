"""The monitor page served by the plc_cell tool: a recorded run of the demo conveyor
(`plc_cell sim --record`, `plc_cell monitor --recording`) scrubbed to chosen instants, stepped
by the program's events, its trends drawn from the recorded history; a failed case's
recording showing its failing check; and a live cell (`plc_cell run --http-tcp`) that
restarts under the page."""
import os
import shutil
import subprocess

import pytest

from conftest import ROOT, conveyor_cell, js, open_page, run, shell, wait, wait_for_server
from pyutil import free_port, stop

# The demo's part sensor (examples/conveyor/conveyor.yaml): a pulse of period 5 s and width
# 2.5 s after a delay of 1 s, so X3 is on from 1.0 s to 3.5 s and from 6.0 s to 8.5 s.
PART_ON_S = 2.0
PART_OFF_S = 4.5


def serve(cmd, scratch, name, port):
    log_path = os.path.join(scratch, name + ".log")
    with open(log_path, "w") as log:
        proc = shell(cmd, stdout=log, stderr=subprocess.STDOUT)
    base = "http://127.0.0.1:%d" % port
    return proc, base, wait_for_server(base, proc, log_path)


@pytest.fixture(scope="module")
def recording(scratch):
    cell = conveyor_cell(scratch, free_port())
    path = os.path.join(scratch, "conveyor.plcrec")
    code, out = run("plc_cell sim --config %s --duration 6s --record %s" % (cell, path))
    assert code == 0 and os.path.exists(path), out
    return path


def seek(driver, seconds):
    js(driver, "const s = document.getElementById('replay-slider'); s.value = arguments[0];"
               "s.dispatchEvent(new Event('change'))", int(seconds * 1e6))
    # The cursor moves to the last scan at or before the instant asked for.
    wait(driver, "the cursor at %.3f s" % seconds, lambda d: (lambda t: t is not None and
         seconds * 1e6 - 10000 <= float(t) <= seconds * 1e6)(d.find_element("id", "clock").get_attribute("data-t-us")))


def watch_value(driver, address):
    return js(driver, "const r = document.querySelector(`#watch tr[data-address='${arguments[0]}'] td.value`);"
                      "return r ? r.textContent : null", address)


def energised(driver, address):
    """Whether a normally open contact of address is drawn passing power."""
    return js(driver, "return [...document.querySelectorAll(`g.el.contact[data-address='${arguments[0]}']"
                      "[data-form='no']`)].some(g => g.classList.contains('on'))", address)


@pytest.fixture
def replay_monitor(recording, scratch):
    """plc_cell monitor on the recording; stopped after the browser's screenshot."""
    port = free_port()
    proc, base, session = serve("plc_cell monitor --recording %s --http-tcp 127.0.0.1:%d" % (recording, port),
                                scratch, "replay", port)
    yield base, session
    stop(proc)


def test_a_recording_scrubs_to_the_chosen_instant(replay_monitor, browser):
    base, session = replay_monitor
    assert session["kind"] == "replay", session
    open_page(browser, base)
    wait(browser, "the time slider", lambda d: d.find_element("id", "replay-slider").is_displayed())
    assert "recording" in browser.find_element("id", "kind").text.lower()
    assert browser.find_element("id", "mode-switch").get_attribute("disabled")
    box = browser.find_element("id", "watch-add")
    box.send_keys("X3")
    browser.find_element("css selector", "#watch-add-form button").click()
    seek(browser, PART_ON_S)
    wait(browser, "X3 = 1 at %.1f s" % PART_ON_S, lambda d: watch_value(d, "X3") == "1")
    wait(browser, "the X3 contact energised at %.1f s" % PART_ON_S, lambda d: energised(d, "X3"))
    seek(browser, PART_OFF_S)
    wait(browser, "X3 = 0 at %.1f s" % PART_OFF_S, lambda d: watch_value(d, "X3") == "0")
    wait(browser, "the X3 contact off at %.1f s" % PART_OFF_S, lambda d: not energised(d, "X3"))
    # One scan back: the cursor moves back in time.
    before = float(browser.find_element("id", "clock").get_attribute("data-t-us"))
    browser.find_element("css selector", "button.step-scan-back").click()
    wait(browser, "the cursor one scan back", lambda d: float(
        d.find_element("id", "clock").get_attribute("data-t-us")) < before)


def cursor_us(driver):
    t = driver.find_element("id", "clock").get_attribute("data-t-us")
    return None if t in (None, "", "undefined") else int(float(t))


def test_step_by_event_moves_to_the_next_change_of_the_programs_addresses(replay_monitor, browser):
    base, _ = replay_monitor
    open_page(browser, base)
    wait(browser, "the time slider", lambda d: d.find_element("id", "replay-slider").is_displayed())
    seek(browser, 0)
    # The 0.01 s clock relay M1920 changes every 5 ms; the first change of the program's
    # own addresses after the start is the part at the stopper, X3 at 1 s.
    browser.find_element("css selector", "button.step-event-fwd").click()
    wait(browser, "the cursor on the part's arrival at 1 s", lambda d: cursor_us(d) == 1000000)
    assert watch_value(browser, "X3") in (None, "1")
    browser.find_element("css selector", "button.step-event-back").click()
    wait(browser, "the cursor back on the first scan", lambda d: cursor_us(d) == 0)


def test_trends_in_a_replay_draw_the_recorded_history(replay_monitor, browser):
    base, _ = replay_monitor
    open_page(browser, base)
    wait(browser, "the time slider", lambda d: d.find_element("id", "replay-slider").is_displayed())
    browser.find_element("css selector", "button[data-tab='trends-panel']").click()
    browser.find_element("id", "trend-add").send_keys("X3")
    browser.find_element("css selector", "#trend-add-form button").click()
    seek(browser, PART_OFF_S)  # the page visits this instant only

    def steps(d):
        rows = js(d, "return window.plcMonitor.trends.rows")
        return [(t, v) for (t, v) in rows] if rows else []

    # The recorded history: X3 OFF from the start, ON at 1.0 s, OFF at 3.5 s, held to the cursor.
    wait(browser, "the trend's recorded history of X3",
         lambda d: steps(d) == [(0, 0), (1.0, 1), (3.5, 0), (PART_OFF_S, 0)])
    assert "recorded changes" in browser.find_element("id", "trend-points").text
    # The time axis zoomed to 20 ms (as a user drags it): every label once.
    js(browser, "window.plcMonitor.trends.graph.updateOptions({dateWindow: [1.475, 1.495]})")
    labels = [e.text for e in browser.find_elements("css selector", "#trend-plot .dygraph-axis-label-x")]
    assert len(labels) >= 3, labels
    assert len(set(labels)) == len(labels), labels
    assert all(1.47 <= float(x) <= 1.50 for x in labels), labels


def test_a_failed_cases_recording_shows_the_failing_check(scratch, browser):
    folder = os.path.join(scratch, "failed")
    os.makedirs(folder, exist_ok=True)
    conveyor_cell(folder, free_port())
    shutil.copy(os.path.join(ROOT, "examples", "conveyor", "too_strict.fails.yaml"), folder)
    code, out = run("plc_cell test %s --record %s" % (os.path.join(folder, "too_strict.fails.yaml"), folder))
    assert code == 1, out
    lines = out.splitlines()
    fail = next(i for i, l in enumerate(lines) if l.startswith("FAIL "))
    check = lines[fail + 1].strip()  # the report's first line of the failure
    path = os.path.join(folder, "the_stopper_lowers_1_s_after_the_part_arrives.plcrec")
    port = free_port()
    proc, base, _ = serve("plc_cell monitor --recording %s --open-at failure --http-tcp 127.0.0.1:%d" % (path, port),
                          scratch, "failed", port)
    try:
        open_page(browser, base)
        wait(browser, "the failing check's text on the page",
             lambda d: d.find_element("id", "replay-failure-text").is_displayed())
        assert browser.find_element("id", "replay-failure-text").text == "failed at 2.000 s: " + check
    finally:
        stop(proc)


def test_the_page_reconnects_after_the_cell_restarts(scratch, browser):
    port = free_port()
    cell = conveyor_cell(scratch, port)
    cmd = "plc_cell run --config %s" % cell
    proc, base, _ = serve(cmd, scratch, "run1", port)
    try:
        open_page(browser, base)
        nets = len(browser.find_elements("css selector", "#ladder .net"))
        stop(proc)
        wait(browser, "the banner saying the connection dropped",
             lambda d: d.find_element("id", "banner").is_displayed() and "lost" in d.find_element("id", "banner").text)
        # The last picture stays while the cell is away.
        assert len(browser.find_elements("css selector", "#ladder .net")) == nets
        last = browser.find_element("id", "clock").get_attribute("data-t-us")
        proc, _, _ = serve(cmd, scratch, "run2", port)
        wait(browser, "the banner gone after the restart", lambda d: not d.find_element("id", "banner").is_displayed())
        wait(browser, "frames of the restarted cell",
             lambda d: d.find_element("id", "clock").get_attribute("data-t-us") != last)
        assert len(browser.find_elements("css selector", "#ladder .net")) == nets
    finally:
        stop(proc)
