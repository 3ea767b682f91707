"""The monitor page on a cell switched to STOP from the page (plc_cell run serving the demo
conveyor, writable: all): no network runs, so no power flow is drawn and the page says why,
while the values are shown as they are; RUN brings the flow back."""
import os
import subprocess

import pytest

from conftest import conveyor_cell, js, open_page, shell, wait, wait_for_server
from pyutil import free_port, stop
from test_monitor_page import watch_add, watch_value


@pytest.fixture(scope="module")
def cell(scratch):
    http = free_port()
    path = conveyor_cell(scratch, http, writable="all")
    log_path = os.path.join(scratch, "run_stop.log")
    with open(log_path, "w") as log:
        proc = shell("plc_cell run --config %s" % path, stdout=log, stderr=subprocess.STDOUT)
    try:
        base = "http://127.0.0.1:%d" % http
        wait_for_server(base, proc, log_path)
        yield {"base": base}
    finally:
        stop(proc)


def energised(driver):
    return js(driver, "return document.querySelectorAll('#ladder .on').length")


def test_in_stop_no_power_flow_is_drawn_and_the_values_are_as_they_are(cell, browser):
    open_page(browser, cell["base"])
    watch_add(browser, "line_running")
    wait(browser, "power flow in RUN", lambda d: energised(d) > 0)
    button = browser.find_element("id", "mode-switch")
    wait(browser, "the STOP button", lambda d: button.text == "STOP" and button.is_enabled())
    button.click()
    try:
        wait(browser, "STOP in the header", lambda d: d.find_element("id", "mode").text == "STOP")
        # The latch M0 keeps its 1 in STOP (only the outputs go off): shown as it is, while
        # no network is drawn carrying power, and the page says why.
        wait(browser, "nothing drawn energised in STOP", lambda d: energised(d) == 0)
        note = browser.find_element("id", "flow-note")
        assert note.is_displayed() and "STOP" in note.text, note.text
        assert watch_value(browser, "line_running") == "1"
        for _ in range(5):  # frame after frame, it stays so
            n = js(browser, "return window.plcMonitor.page.frames")
            wait(browser, "a later frame", lambda d: js(d, "return window.plcMonitor.page.frames") > n)
            assert energised(browser) == 0
    finally:
        wait(browser, "the RUN button", lambda d: button.text == "RUN" and button.is_enabled())
        button.click()
    wait(browser, "power flow again in RUN", lambda d: energised(d) > 0)
    assert not browser.find_element("id", "flow-note").is_displayed()
