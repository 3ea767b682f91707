"""The monitor page on the demo conveyor (examples/conveyor) served by plc_node (roslaunch
cell_sim.launch, the monitor and its writable ranges from the cell YAML's servers.http), in
headless chromium: the networks drawn, power flow following an input set through plc_node's
~write service, a watch value following the program, forcing inside the writable ranges and
forced points marked with their state, the controls the ranges refuse disabled with the
reason, the log of the page's actions (once each, on the cell's clock), a trend collecting
points, the layout at 1400 and 1024 px, and the networks numbered as coverage numbers them."""
import json
import os
import re
import subprocess

import pytest
from selenium.common.exceptions import NoSuchElementException, StaleElementReferenceException

from conftest import conveyor_cell, get_json, js, open_page, ros_env, run, shell, wait, wait_for_server
from pyutil import ROOT, free_port, stop

PROGRAM = os.path.join(ROOT, "examples", "conveyor", "conveyor.il")


@pytest.fixture(scope="module")
def cell(scratch):
    http = free_port()
    master = free_port()
    env = ros_env(master)
    path = conveyor_cell(scratch, http)
    log_path = os.path.join(scratch, "roslaunch.log")
    with open(log_path, "w") as log:
        proc = shell("roslaunch -p %d plc_cell cell_sim.launch cell:=%s" % (master, path), env,
                     stdout=log, stderr=subprocess.STDOUT)
    try:
        base = "http://127.0.0.1:%d" % http
        wait_for_server(base, proc, log_path)
        yield {"base": base, "env": env}
    finally:
        stop(proc)


def program_lines():
    return [l.split(";")[0].split() for l in open(PROGRAM)]


def contact(driver, address):
    return driver.find_elements("css selector", 'g.el.contact[data-address="%s"]' % address)


def energised(driver, address):
    """Whether a normally open contact of address is drawn passing power."""
    return js(driver, "return [...document.querySelectorAll(`g.el.contact[data-address='${arguments[0]}']"
                      "[data-form='no']`)].some(g => g.classList.contains('on'))", address)


def watch_add(driver, address):
    box = driver.find_element("id", "watch-add")
    box.clear()
    box.send_keys(address)
    driver.find_element("css selector", "#watch-add-form button").click()
    return wait(driver, "a watch row for %s" % address,
                lambda d: d.find_elements("css selector", '#watch tr[data-address="%s"]' % address))[0]


def watch_value(driver, address):
    return js(driver, "const r = document.querySelector(`#watch tr[data-address='${arguments[0]}'] td.value`);"
                      "return r ? r.textContent : null", address)


def in_row(driver, address, what, action):
    """action(row) on the watch row of address, found afresh until it holds: the page redraws
    the table (a row added, a reconnection), and a row found before a redraw is gone."""
    def attempt(d):
        try:
            action(d.find_element("css selector", '#watch tr[data-address="%s"]' % address))
            return True
        except (NoSuchElementException, StaleElementReferenceException):
            return False
    wait(driver, "%s in the watch row of %s" % (what, address), attempt)


def row_click(driver, address, button):
    in_row(driver, address, button, lambda row: row.find_element("css selector", button).click())


def page_write(driver, address, value):
    def write(row):
        field = row.find_element("css selector", "input.write-value")
        field.clear()
        field.send_keys(str(value))
        row.find_element("css selector", "button.write-button").click()
    in_row(driver, address, "a write of %s" % value, write)


def log_lines(driver):
    return js(driver, "return [...document.querySelectorAll('#log li')].map(li => li.className + ' ' + li.textContent)")


def tab(driver, panel):
    driver.find_element("css selector", '.tabs button[data-tab="%s"]' % panel).click()


def test_the_page_draws_the_conveyors_networks(cell, browser):
    open_page(browser, cell["base"])
    # Every coil, contact and timer of the program is drawn, with the cell's signal names.
    words = program_lines()
    coils = {w[1] for w in words if len(w) == 2 and w[0] in ("OUT", "SET", "RST")}
    contacts = {w[-1] for w in words if w and w[0] in ("ORG", "AND", "OR", "LD") and re.match(r"^[XYMTC]\d+$", w[-1])}
    timers = {w[1] for w in words if w and w[0] == "TMR"}
    assert coils and contacts and timers
    wait(browser, "every coil, contact and timer of conveyor.il", lambda d: all(
        d.find_elements("css selector", 'g.el[data-address="%s"]' % a) for a in coils | contacts | timers))
    assert browser.find_elements("css selector", 'g.el.coil[data-address="Y0"]')
    names = js(browser, "return document.querySelector('#ladder').textContent")
    for name in ("start_button", "conveyor_run", "part_present"):
        assert name in names
    # The IL comment above the first network.
    first = browser.find_element("css selector", "#ladder .net .comment").text
    assert "Start/stop latch" in first, first
    assert browser.find_element("id", "kind").text.lower() == "live cell"


def test_search_and_subscription_follow_what_is_shown(cell, browser):
    browser.set_window_size(1400, 500)
    open_page(browser, cell["base"])
    total = len(browser.find_elements("css selector", "#ladder .net"))
    subscribed = lambda d: js(d, "return window.plcMonitor.live.subscription.networks")  # noqa: E731
    # Only the networks on the screen (and a margin) are subscribed to.
    wait(browser, "a subscription to the first networks", lambda d: 0 in subscribed(d))
    assert len(subscribed(browser)) < total, subscribed(browser)
    js(browser, "document.querySelector('#ladder .net:last-child').scrollIntoView()")
    wait(browser, "the last network subscribed once in view", lambda d: total - 1 in subscribed(d))
    assert 0 not in subscribed(browser)
    # Searching by address keeps the networks that mention it: T51 is timed in one, read in two.
    browser.find_element("id", "search").send_keys("T51")
    shown = lambda d: [n for n in d.find_elements("css selector", "#ladder .net") if n.is_displayed()]  # noqa: E731
    wait(browser, "three networks mentioning T51", lambda d: len(shown(d)) == 3)
    assert all("T51" in n.text for n in shown(browser))


def test_a_contact_lights_up_when_its_input_is_set_through_ros(cell, browser):
    open_page(browser, cell["base"])
    wait(browser, "the X0 contact", lambda d: contact(d, "X0"))
    wait(browser, "X0 (start button, not pressed) drawn off", lambda d: not energised(d, "X0"))
    code, out = run("rosservice call /plc_node/write X0 '[1]'", cell["env"])
    assert code == 0 and "success: True" in out, out
    try:
        wait(browser, "X0 drawn energised after ~write X0 [1]", lambda d: energised(d, "X0"))
    finally:
        code, out = run("rosservice call /plc_node/write X0 '[0]'", cell["env"])
    assert code == 0, out
    wait(browser, "X0 drawn off again after ~write X0 [0]", lambda d: not energised(d, "X0"))


def watch_format(driver, address, fmt):
    in_row(driver, address, "format %s" % fmt, lambda row: js(
        driver, "arguments[0].value = arguments[1]; arguments[0].dispatchEvent(new Event('change'))",
        row.find_element("css selector", "select.format"), fmt))


def test_a_watch_value_follows_the_program(cell, browser):
    open_page(browser, cell["base"])
    for a in ("X3", "Y0"):
        watch_add(browser, a)
    # The belt (Y0) stops while a part waits at the stopper (X3, simulated: 2.5 s of every 5 s)
    # until the stopper is lowered, and runs while none is there: Y0 = M0 & (!X3 | Y1).
    wait(browser, "a part at the stopper, the belt stopped",
         lambda d: (watch_value(d, "X3"), watch_value(d, "Y0")) == ("1", "0"))
    wait(browser, "no part, the belt running", lambda d: (watch_value(d, "X3"), watch_value(d, "Y0")) == ("0", "1"))


def test_a_watch_row_writes_in_its_format(cell, browser):
    open_page(browser, cell["base"])
    watch_add(browser, "D10")
    watch_format(browser, "D10", "signed")
    page_write(browser, "D10", -5)
    wait(browser, "D10 = -5 (signed)", lambda d: watch_value(d, "D10") == "-5")
    watch_format(browser, "D10", "hex")
    wait(browser, "D10 = 0xFFFB (hex)", lambda d: watch_value(d, "D10") == "0xFFFB")
    code, out = run("rosservice call /plc_node/read D10 1", cell["env"])
    assert code == 0 and "65531" in out, out
    # 32-bit: the double word D10..D11 (DD10), low word first.
    watch_format(browser, "D10", "32-bit")
    page_write(browser, "D10", 70000)
    wait(browser, "D10 = 70000 (32-bit)", lambda d: watch_value(d, "D10") == "70000")
    code, out = run("rosservice call /plc_node/read D10 2", cell["env"])
    assert code == 0 and "[4464, 1]" in out, out
    wait(browser, "the write in the log", lambda d: any("D10" in l for l in log_lines(d)))


def test_forcing_inside_the_writable_ranges(cell, browser):
    open_page(browser, cell["base"])
    watch_add(browser, "X3")
    row_click(browser, "X3", "button.force-on")
    try:
        wait(browser, "X3 forced on in the watch table", lambda d: watch_value(d, "X3") == "1 (forced ON)")
        tab(browser, "status-panel")
        wait(browser, "X3 among the forced points", lambda d: "X3" in d.find_element("id", "status-forced").text)
    finally:
        tab(browser, "watch-panel")
        row_click(browser, "X3", "button.force-release")
    tab(browser, "status-panel")
    wait(browser, "X3 no longer forced", lambda d: "none" in d.find_element("id", "status-forced").text)


def test_a_trend_collects_points(cell, browser):
    open_page(browser, cell["base"])
    tab(browser, "trends-panel")
    box = browser.find_element("id", "trend-add")
    box.send_keys("TR50 M0")
    browser.find_element("css selector", "#trend-add-form button").click()
    wait(browser, "20 points in the trend",
         lambda d: int(d.find_element("id", "trend-points").get_attribute("data-count") or 0) >= 20)
    assert browser.find_elements("css selector", "#trend-plot canvas"), "dygraphs drew nothing"
    # Points are at distinct instants of the cell's clock, in order.
    ts = js(browser, "return window.plcMonitor.trends.rows.map(r => r[0])")
    assert ts == sorted(ts) and len(set(ts)) == len(ts), ts


def coverage_class(driver, address, form):
    return js(driver, "const g = document.querySelector(`g.el.contact[data-address='${arguments[0]}']"
                      "[data-form='${arguments[1]}']`); return g ? g.getAttribute('class') : ''", address, form)


def test_the_coverage_overlay_colours_what_ran(cell, browser):
    open_page(browser, cell["base"])
    browser.find_element("id", "coverage-toggle").click()
    # Since coverage started (the first request): the start button X0 was evaluated but never
    # closed (the line latched at the first scan), the latch M0 closed.
    wait(browser, "X0 evaluated, never energised", lambda d: "cov-off" in coverage_class(d, "X0", "no"))
    wait(browser, "M0 energised", lambda d: "cov-on" in coverage_class(d, "M0", "no"))
    browser.find_element("id", "coverage-toggle").click()
    wait(browser, "the overlay off again", lambda d: "cov-" not in coverage_class(d, "X0", "no"))


def status_forced(driver, address):
    return js(driver, "const li = document.querySelector(`#status-forced li[data-address='${arguments[0]}']`);"
                      "return li ? li.textContent : null", address)


def force_tags(driver, address):
    """The tags of the contacts and coils of address: '' where not forced."""
    return js(driver, "return [...document.querySelectorAll(`#ladder g.el[data-address='${arguments[0]}']`)]"
                      ".filter(g => g.querySelector('.forcetag')).map(g => g.querySelector('.forcetag').textContent)",
              address)


def test_forced_points_are_marked_with_their_state_on_the_ladder_in_the_table_and_in_status(cell, browser):
    open_page(browser, cell["base"])
    watch_add(browser, "part_present")  # X3, by the cell's name
    try:
        row_click(browser, "part_present", "button.force-on")
        # Every contact of X3 on the ladder (networks 2 and 3), the watch row, the Status tab.
        wait(browser, "X3's contacts tagged forced ON", lambda d: force_tags(d, "X3") == ["F ON", "F ON"])
        wait(browser, "the watch row marked forced ON",
             lambda d: "forced ON" in (watch_value(d, "part_present") or ""))
        assert js(browser, "return document.querySelector(`#watch tr[data-address='part_present']`).dataset.forced") == "on"
        tab(browser, "status-panel")
        wait(browser, "X3 in Status with its name and state",
             lambda d: status_forced(d, "X3") == "X3 part_present: forced ON")
        tab(browser, "watch-panel")
        row_click(browser, "part_present", "button.force-off")
        wait(browser, "X3's contacts tagged forced OFF", lambda d: force_tags(d, "X3") == ["F OFF", "F OFF"])
        wait(browser, "the watch row marked forced OFF",
             lambda d: "forced OFF" in (watch_value(d, "part_present") or ""))
        # Points not forced carry no tag.
        assert set(force_tags(browser, "X4")) == {""}, force_tags(browser, "X4")
    finally:
        tab(browser, "watch-panel")
        row_click(browser, "part_present", "button.force-release")
    wait(browser, "X3's tags gone once released", lambda d: force_tags(d, "X3") == ["", ""])


def control(driver, address, selector):
    return js(driver, "const b = document.querySelector(`#watch tr[data-address='${arguments[0]}'] ${arguments[1]}`);"
                      "return b ? [b.disabled, b.title] : null", address, selector)


def test_controls_the_server_would_refuse_are_disabled_with_the_reason(cell, browser):
    open_page(browser, cell["base"])
    writable = get_json(cell["base"] + "/api/session")["writable"]
    for a in ("Y0", "X5", "D10"):
        watch_add(browser, a)
    refused = [True, "Y0 is not writable (writable: %s)" % writable]
    for selector in ("button.write-button", "input.write-value", "button.force-on", "button.force-off",
                     "button.force-release"):
        wait(browser, "Y0's %s disabled, the reason its tooltip" % selector,
             lambda d: control(d, "Y0", selector) == refused)
    for selector in ("button.write-button", "button.force-on", "button.force-release"):
        assert control(browser, "X5", selector)[0] is False, selector
    assert control(browser, "D10", "button.write-button")[0] is False
    # RUN/STOP needs writable: all.
    button = browser.find_element("id", "mode-switch")
    wait(browser, "RUN/STOP disabled, the reason its tooltip", lambda d: button.get_attribute("disabled") and
         button.get_attribute("title") == "RUN/STOP needs writable: all (writable: %s)" % writable)


def log_entries(driver, text):
    return js(driver, "return [...document.querySelectorAll('#log li')].filter(li => li.textContent.includes("
                      "arguments[0])).map(li => [li.className, li.querySelector('.when').textContent,"
                      " li.querySelector('.text').textContent])", text)


def frames_pass(driver, n):
    """Until the page has taken n more frames: time for anything still on its way to arrive."""
    start = js(driver, "return window.plcMonitor.page.frames")
    wait(driver, "%d more frames" % n, lambda d: js(d, "return window.plcMonitor.page.frames") >= start + n)


def test_the_log_shows_each_action_of_the_page_once_on_the_cells_clock(cell, browser):
    open_page(browser, cell["base"])
    watch_add(browser, "D11")
    page_write(browser, "D11", 5)
    wait(browser, "D11 = 5 in the table", lambda d: watch_value(d, "D11") == "5")
    wait(browser, "the write in the log", lambda d: log_entries(d, "D11 = 5"))
    frames_pass(browser, 5)
    entries = log_entries(browser, "D11 = 5")
    assert len(entries) == 1, entries
    assert re.match(r"^\d+\.\d{3} s$", entries[0][1]), entries  # the cell's clock, not the wall's
    # Refused (a value out of range): once too, as an error.
    page_write(browser, "D11", 70000)
    refusal = lambda d: [e for e in log_entries(d, "D11") if "refused" in e[2]]  # noqa: E731
    wait(browser, "the refusal in the log", refusal)
    frames_pass(browser, 5)
    entries = refusal(browser)
    assert len(entries) == 1 and entries[0][0] == "error", entries
    assert re.match(r"^\d+\.\d{3} s$", entries[0][1]), entries


@pytest.mark.parametrize("width", [1400, 1024])
def test_the_layout_keeps_every_column_and_draws_what_fits_without_scrollbars(cell, browser, width):
    browser.set_window_size(width, 900)
    open_page(browser, cell["base"])
    for a in ("X0", "D10", "conveyor_run", "stopper_lower"):
        watch_add(browser, a)
    wait(browser, "values in the watch rows", lambda d: watch_value(d, "stopper_lower") not in (None, ""))
    box = js(browser, """
      const side = document.querySelector('.side'), r = side.getBoundingClientRect();
      const right = r.left + side.clientLeft + side.clientWidth;
      return {scroll: side.scrollWidth, client: side.clientWidth, right,
              removes: [...document.querySelectorAll('#watch button.remove')].map(b => b.getBoundingClientRect().right),
              headers: [...document.querySelectorAll('#watch th')].map(h => h.getBoundingClientRect().right)};""")
    assert box["scroll"] <= box["client"], box
    assert len(box["removes"]) == 4 and max(box["removes"] + box["headers"]) <= box["right"], box
    # A network's drawing: the box of what is drawn in it (its strokes and texts).
    nets = js(browser, """
      return [...document.querySelectorAll('#ladder .net')].filter(n => n.querySelector('svg')).map(n => {
        const s = getComputedStyle(n), box = n.querySelector('svg').getBBox();
        const room = n.clientWidth - parseFloat(s.paddingLeft) - parseFloat(s.paddingRight);
        return {id: n.id, drawing: box.x + box.width + 2, room, scroll: n.scrollWidth, client: n.clientWidth};});""")
    fitting = [n for n in nets if n["drawing"] <= n["room"]]
    assert len(fitting) >= len(nets) - 1, nets  # at 1024 px only the timer box of network 3 is wider
    for n in fitting:
        assert n["scroll"] <= n["client"], n  # no horizontal scrollbar on a drawing that fits
    # A comment of two lines keeps them.
    comment = js(browser, "return document.querySelector('#net-1 .comment').innerText")
    assert "stopper,\nor while" in comment, repr(comment)


def test_networks_are_numbered_as_coverage_numbers_them_with_their_line(cell, browser, scratch):
    out = os.path.join(scratch, "coverage.json")
    code, text = run("plc_cell test %s -k 'counts every part' --coverage-json %s" % (
        os.path.join(ROOT, "examples", "conveyor", "conveyor.scenario.yaml"), out), cell["env"])
    assert code == 0, text
    coverage = [("network %d (line %d)" % (n["number"], n["line"]))
                for n in json.load(open(out))["programs"][0]["networks"]]
    open_page(browser, cell["base"])
    shown = js(browser, "return [...document.querySelectorAll('#ladder .net .netno')].map(e => e.textContent)")
    assert [s for s in shown if s.startswith("network")] == coverage, (shown, coverage)
    # END is no network: its line alone.
    assert shown[-1] == "line 45", shown
