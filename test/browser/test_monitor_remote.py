"""The monitor page on a real PLC, tried from outside: `plc_cell monitor --fatek` polling a
`plc_cell run` that serves the demo conveyor over FATEK. Points forced in the PLC (through its
own monitor, not this one) are shown forced; the scan panel gives no polling figures as the
PLC's; and when the PLC goes away (its process stopped by its pid) the page says so in the
red banner, marks every value stale with its age, draws no power flow and logs the lost link
once, until the PLC is back (started again on its port), when all of that clears."""
import json
import os
import re
import subprocess
import urllib.request

import pytest

from conftest import conveyor_cell, js, open_page, shell, wait, wait_for_server
from pyutil import free_port, stop
from test_monitor_page import force_tags, log_entries, status_forced, tab, watch_add, watch_value


class Plc:
    """plc_cell run standing in for the PLC: FATEK on fatek_port, its own monitor (writable:
    all) on http_port for what is done to it from outside."""

    def __init__(self, scratch):
        self.scratch = scratch
        self.fatek_port = free_port()
        self.http_port = free_port()
        self.config = conveyor_cell(scratch, self.http_port, writable="all")
        self.proc = None
        self.runs = 0

    def start(self):
        self.runs += 1
        log_path = os.path.join(self.scratch, "plc_%d.log" % self.runs)
        with open(log_path, "w") as log:
            self.proc = shell("plc_cell run --config %s --fatek-tcp 127.0.0.1:%d" % (self.config, self.fatek_port),
                              stdout=log, stderr=subprocess.STDOUT)
        self.base = "http://127.0.0.1:%d" % self.http_port
        self.token = wait_for_server(self.base, self.proc, log_path)["token"]

    def stop(self):
        stop(self.proc)

    def force(self, address, action):
        body = json.dumps({"address": address, "action": action}).encode()
        req = urllib.request.Request(self.base + "/api/force", data=body, method="POST",
                                     headers={"X-Plc-Token": self.token, "Content-Type": "application/json"})
        with urllib.request.urlopen(req, timeout=5) as r:
            assert json.loads(r.read().decode()) == {"ok": True}


@pytest.fixture(scope="module")
def remote(scratch):
    plc = Plc(scratch)
    plc.start()
    http = free_port()
    log_path = os.path.join(scratch, "monitor.log")
    with open(log_path, "w") as log:
        mon = shell("plc_cell monitor --fatek 127.0.0.1:%d --config %s --http-tcp 127.0.0.1:%d --http-writable all"
                    % (plc.fatek_port, plc.config, http), stdout=log, stderr=subprocess.STDOUT)
    try:
        base = "http://127.0.0.1:%d" % http
        wait_for_server(base, mon, log_path)
        yield {"base": base, "plc": plc}
    finally:
        stop(mon)
        plc.stop()


def energised(driver):
    return js(driver, "return document.querySelectorAll('#ladder .on').length")


def banner(driver):
    return js(driver, "const b = document.getElementById('banner'); return b.hidden ? '' : b.textContent")


def test_the_plcs_forced_points_and_no_polling_figures_as_its_scan(remote, browser):
    open_page(browser, remote["base"])
    assert browser.find_element("id", "kind").text.lower() == "remote plc"
    remote["plc"].force("X3", "on")  # in the PLC, through its own monitor
    try:
        wait(browser, "X3's contacts tagged forced ON", lambda d: force_tags(d, "X3") == ["F ON", "F ON"])
        tab(browser, "status-panel")
        wait(browser, "X3 in Status with its name and state",
             lambda d: status_forced(d, "X3") == "X3 part_present: forced ON")
        text = browser.find_element("id", "status-forced").text
        assert "read from the PLC" in text, text
        scan = browser.find_element("id", "status-scan").text
        assert "scan figures: not known" in scan and "cycle" not in scan and "wake" not in scan, scan
    finally:
        remote["plc"].force("X3", "release")
    wait(browser, "X3 released in the PLC, its tags gone", lambda d: force_tags(d, "X3") == ["", ""])


def test_a_plc_that_goes_away_and_comes_back(remote, browser):
    plc = remote["plc"]
    open_page(browser, remote["base"])
    watch_add(browser, "line_running")
    wait(browser, "power flow from the PLC's values", lambda d: energised(d) > 0)
    assert banner(browser) == ""
    plc.stop()
    try:
        wait(browser, "the red banner", lambda d: "No current values" in banner(d) and "link down" in banner(d))
        # Every value stale, with its age; no power flow from them; the mode not known.
        wait(browser, "the values 2 s old", lambda d: re.search(r"\((\d+\.\d) s old", watch_value(d, "line_running") or "")
             and float(re.search(r"\((\d+\.\d) s old", watch_value(d, "line_running")).group(1)) >= 2.0)
        assert watch_value(browser, "line_running").startswith("1 (")
        assert energised(browser) == 0
        assert js(browser, "return document.getElementById('ladder').classList.contains('stale')")
        assert browser.find_element("id", "mode").text == "RUN/STOP ?"
        assert js(browser, "return document.body.classList.contains('disconnected')")
        # Twenty frames and more since it went: the lost link is in the log once.
        tab(browser, "log-panel")
        assert len(log_entries(browser, "link down")) == 1, log_entries(browser, "link down")
        tab(browser, "watch-panel")
    finally:
        plc.start()
    wait(browser, "the banner gone once the PLC answers", lambda d: banner(d) == "")
    wait(browser, "power flow again", lambda d: energised(d) > 0)
    assert re.fullmatch(r"\d+", watch_value(browser, "line_running")), watch_value(browser, "line_running")
    tab(browser, "status-panel")
    # The link's state in Status: running, up, and no error left over from the outage.
    wait(browser, "the link up in Status, no old error",
         lambda d: js(d, "return document.querySelectorAll('#status-servers td')[1].textContent") == "running")
    tab(browser, "log-panel")
    assert len(log_entries(browser, "link down")) == 1
    wait(browser, "the link's return in the log once", lambda d: len(log_entries(d, "values read again")) == 1)
