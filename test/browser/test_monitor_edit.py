"""The monitor's Edit tab on the demo conveyor (plc_cell run, writable: all, edit: true; the
cell's gate: its scenario file and 20 s of exploration): the running program's IL
highlighted, errors at their line, the changed networks drawn old beside new, Test showing
the gate's report, a change that breaks the interlock property refused with that property's
report, the part counter's preset applied live, Undo restoring it, and the change log. A
server without edit: true offers no Apply."""
import json
import os
import shutil
import subprocess
import time
import urllib.error
import urllib.request

import pytest

from conftest import ROOT, WAIT, js, open_page, shell, wait, wait_for_server
from pyutil import free_port, stop

SRC = os.path.join(ROOT, "examples", "conveyor")
ORIGINAL = open(os.path.join(SRC, "conveyor.il")).read()
BROKEN = ORIGINAL.replace("OR      Y1\nANDLD", "OR      Y2\nANDLD")
HARMLESS = ORIGINAL.replace("CTR     C0 9999", "CTR     C0 5000")
assert BROKEN != ORIGINAL and HARMLESS != ORIGINAL


def serve(folder, name, edit, mutate=False):
    """The demo's files in folder, served with the monitor; its base URL and process. mutate:
    the gate runs mutation testing of the lines a change writes."""
    os.makedirs(folder, exist_ok=True)
    for f in ("conveyor.il", "conveyor.scenario.yaml"):
        shutil.copy(os.path.join(SRC, f), folder)
    http = free_port()
    text = open(os.path.join(SRC, "conveyor.yaml")).read()
    if mutate:
        assert "  explore: 20s\n" in text
        text = text.replace("  explore: 20s\n", "  explore: 20s\n  mutate: true\n")
    text += "servers:\n  http:\n    tcp: 127.0.0.1:%d\n    writable: all\n    edit: %s\n" % (http, edit)
    path = os.path.join(folder, "conveyor.yaml")
    with open(path, "w") as f:
        f.write(text)
    log_path = os.path.join(folder, name + ".log")
    with open(log_path, "w") as log:
        proc = shell("plc_cell run --config %s" % path, stdout=log, stderr=subprocess.STDOUT)
    base = "http://127.0.0.1:%d" % http
    try:
        wait_for_server(base, proc, log_path)
    except BaseException:
        stop(proc)
        raise
    return base, proc


@pytest.fixture(scope="module")
def cell(scratch):
    folder = os.path.join(scratch, "edit")
    base, proc = serve(folder, "edit", "true")
    try:
        yield {"base": base, "program": os.path.join(folder, "conveyor.il")}
    finally:
        stop(proc)


def post(base, path, body):
    token = json.loads(urllib.request.urlopen(base + "/api/session", timeout=5).read())["token"]
    req = urllib.request.Request(base + path, data=json.dumps(body).encode(), method="POST",
                                 headers={"Content-Type": "application/json", "X-Plc-Token": token})
    with urllib.request.urlopen(req, timeout=5) as r:
        return json.loads(r.read())


def get(base, path):
    return json.loads(urllib.request.urlopen(base + path, timeout=5).read())


def open_edit(driver, base):
    open_page(driver, base)
    driver.find_element("id", "edit-tab").click()
    wait(driver, "the running program in the editor",
         lambda d: "CTR     C0" in (js(d, "return window.plcMonitor.edit.text()") or ""))


def set_text(driver, text):
    js(driver, "window.plcMonitor.edit.setText(arguments[0])", text)


def diff_rows(driver):
    return js(driver, "return document.querySelectorAll('#edit-diff .diff-row').length")


def gate_shown(driver):
    return js(driver, "const g = document.getElementById('edit-gate'); return g ? g.dataset.passed : null")


def status(driver):
    return driver.find_element("id", "edit-status").text


def test_the_program_is_highlighted_and_errors_are_at_their_line(cell, browser):
    open_edit(browser, cell["base"])
    wait(browser, "CodeMirror's IL highlighting",
         lambda d: js(d, "return document.querySelectorAll('#edit-editor .CodeMirror .cm-keyword').length") > 5)
    assert js(browser, "return document.querySelectorAll('#edit-editor .cm-comment').length") > 0
    set_text(browser, "ORG X0\nOUT Y0\nFUN 999\nEND\n")
    wait(browser, "the error listed at line 3",
         lambda d: d.find_elements("css selector", "#edit-errors li") and
         d.find_element("css selector", "#edit-errors li").text.startswith("line 3"))
    assert js(browser, "return document.querySelectorAll('.il-error-line').length") == 1
    assert js(browser, "return window.plcMonitor.edit.cm.getLineHandle(2).bgClass") == "il-error-line"
    assert not browser.find_element("id", "edit-apply").is_enabled()


def test_a_change_that_breaks_the_interlock_is_refused_with_the_propertys_report(cell, browser):
    before = get(cell["base"], "/api/edit")["hash"]
    open_edit(browser, cell["base"])
    set_text(browser, BROKEN)
    wait(browser, "one changed network drawn old beside new", lambda d: diff_rows(d) == 1)
    assert js(browser, "return document.querySelectorAll('#edit-diff .diff-old svg, #edit-diff .diff-new svg').length") == 2
    assert js(browser, "return document.querySelector('#edit-diff .diff-new').textContent").count("Y2") >= 1
    test = browser.find_element("id", "edit-test")
    wait(browser, "Test enabled", lambda d: test.is_enabled())
    test.click()
    wait(browser, "the gate's verdict", lambda d: gate_shown(d) == "false")
    report = browser.find_element("id", "edit-report").text
    assert "property always: pick_request -> not conveyor_run violated" in report, report
    assert not browser.find_element("id", "edit-apply").is_enabled()
    assert browser.find_element("id", "edit-force").is_displayed()
    assert not browser.find_element("id", "edit-force-apply").is_enabled(), "apply anyway needs a reason"
    # Apply asked for anyway (as a page could): refused by the server, with the report.
    job = post(cell["base"], "/api/edit/apply", {"text": BROKEN})
    # The gate runs in a process of its own: bounded in time, not in a count of polls that a
    # loaded machine's gate outlasts.
    deadline = time.monotonic() + WAIT
    while job["state"] != "done" and time.monotonic() < deadline:
        time.sleep(0.05)  # polling the job, not waiting for a result
        job = get(cell["base"], "/api/edit/job")
    assert job["state"] == "done", "the gate's job not done in %.0f s: %s" % (WAIT, job)
    assert job["result"]["result"] == "refused", job
    assert "pick_request -> not conveyor_run" in json.dumps(job["result"]["gate"]["report"])
    assert get(cell["base"], "/api/edit")["hash"] == before, "the running program is untouched"
    assert open(cell["program"]).read() == ORIGINAL
    browser.refresh()
    open_edit(browser, cell["base"])
    wait(browser, "the refusal in the change log",
         lambda d: js(d, "return [...document.querySelectorAll('#edit-log-table tr')].some(r => r.dataset.result === 'refused')"))


def ladder_has(driver, text):
    return js(driver, "return document.getElementById('ladder').textContent.includes(arguments[0])", text)


def test_the_counters_preset_goes_live_and_undo_restores_it(cell, browser):
    open_edit(browser, cell["base"])
    set_text(browser, HARMLESS)
    wait(browser, "one changed network", lambda d: diff_rows(d) == 1)
    apply = browser.find_element("id", "edit-apply")
    assert not apply.is_enabled() and "Test" in apply.get_attribute("title")
    browser.find_element("id", "edit-test").click()
    wait(browser, "the gate passed", lambda d: gate_shown(d) == "true")
    wait(browser, "Apply enabled once the gate passed", lambda d: apply.is_enabled())
    scan = int(browser.find_element("id", "clock").get_attribute("data-scan"))
    apply.click()
    wait(browser, "the change applied", lambda d: status(d).startswith("apply: applied"))
    wait(browser, "the ladder redrawn with the new preset", lambda d: ladder_has(d, "5000"))
    wait(browser, "the cell scanning on", lambda d: int(d.find_element("id", "clock").get_attribute("data-scan")) > scan)
    assert js(browser, "return window.plcMonitor.page.status.mode") == "run"
    assert open(cell["program"]).read() == HARMLESS
    undo = browser.find_element("id", "edit-undo")
    wait(browser, "Undo enabled", lambda d: undo.is_enabled())
    undo.click()
    wait(browser, "the undo applied", lambda d: status(d).startswith("undo: applied"))
    wait(browser, "the ladder back at 9999", lambda d: ladder_has(d, "9999") and not ladder_has(d, "5000"))
    wait(browser, "the editor back at the old program", lambda d: js(d, "return window.plcMonitor.edit.text()") == ORIGINAL)
    assert open(cell["program"]).read() == ORIGINAL
    results = js(browser, "return [...document.querySelectorAll('#edit-log-table tr')].map(r => r.dataset.result)")
    assert results[:2] == ["applied", "applied"], results  # newest first: the undo, the change


def test_without_edit_the_server_offers_no_apply(scratch, browser):
    base, proc = serve(os.path.join(scratch, "no_edit"), "no_edit", "false")
    try:
        open_edit(browser, base)
        set_text(browser, HARMLESS)
        wait(browser, "the change checked", lambda d: diff_rows(d) == 1)
        apply = browser.find_element("id", "edit-apply")
        assert not apply.is_enabled()
        assert "servers.http.edit" in apply.get_attribute("title")
        assert not browser.find_element("id", "edit-undo").is_enabled()
        with pytest.raises(urllib.error.HTTPError) as refused:
            post(base, "/api/edit/apply", {"text": HARMLESS})
        assert refused.value.code == 409
    finally:
        stop(proc)


def test_a_change_no_case_checks_is_refused_with_its_surviving_mutants(scratch, browser):
    """gate.mutate: a new network nothing checks passes every case, and its mutants survive."""
    base, proc = serve(os.path.join(scratch, "mutate"), "mutate", "true", mutate=True)
    try:
        untested = ORIGINAL.replace("\nEND", "\nORG     X3\nOUT     M500\nEND")
        line = ORIGINAL[:ORIGINAL.index("\nEND")].count("\n") + 2
        open_edit(browser, base)
        set_text(browser, untested)
        wait(browser, "the new network drawn", lambda d: diff_rows(d) == 1)
        test = browser.find_element("id", "edit-test")
        wait(browser, "Test enabled", lambda d: test.is_enabled())
        test.click()
        wait(browser, "the gate's verdict", lambda d: gate_shown(d) == "false")
        report = browser.find_element("id", "edit-report").text
        assert "mutant(s) of the changed lines survived" in report, report
        assert "FAIL mutant line %d: ORG X3 \u2192 ORG NOT X3" % line in report, report
        assert "FAIL mutant line %d: OUT M500 \u2192 (deleted)" % (line + 1) in report, report
        assert not browser.find_element("id", "edit-apply").is_enabled()
    finally:
        stop(proc)
