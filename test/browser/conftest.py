"""What the browser tests share: the cell or recording they serve, a headless chromium driven
by selenium (Debian's chromium, chromium-driver, python3-selenium), bounded waits on what the
page shows, and a screenshot of every test kept beside its JUnit results."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

import pytest
from selenium import webdriver
from selenium.common.exceptions import StaleElementReferenceException
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.support.ui import WebDriverWait

# realpath: run from the workspace, this file is reached through its links to the package.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
from pyutil import ROOT, devel  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from ros_loopback import loopback_env  # noqa: E402

WAIT = 30.0  # seconds: every wait on the page or on a process is bounded by this
WRITABLE = "X0-X7,M800-M899,D0-D99"


def ros_env(master_port):
    return loopback_env(dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % master_port, PYTHONUNBUFFERED="1"))


def shell(cmd, env=None, **kw):
    """cmd in bash with the devel space sourced, as a user's shell."""
    script = "source %s/setup.bash >/dev/null 2>&1\n%s\n" % (devel(), cmd)
    return subprocess.Popen(["bash", "-c", script], env=env or os.environ, stdin=subprocess.DEVNULL,
                            start_new_session=True, **kw)


def run(cmd, env=None, limit=120):
    p = shell(cmd, env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    out, _ = p.communicate(timeout=limit)
    return p.returncode, out.decode(errors="replace")


def get_json(url):
    with urllib.request.urlopen(url, timeout=5) as r:
        return json.loads(r.read().decode())


def wait_for_server(base, proc, log_path, limit=60.0):
    """Until GET /api/session answers; fails with the process's output if it died or never did."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            break
        try:
            return get_json(base + "/api/session")
        except (urllib.error.URLError, ConnectionError, OSError, ValueError):
            time.sleep(0.2)  # polling the server coming up, not waiting for a result
    with open(log_path, errors="replace") as f:
        pytest.fail("the monitor at %s did not come up; its output:\n%s" % (base, f.read()[-4000:]))


def conveyor_cell(folder, http_port, writable=WRITABLE):
    """The demo conveyor with the monitor on http_port and writable ranges, in folder."""
    src = os.path.join(ROOT, "examples", "conveyor")
    shutil.copy(os.path.join(src, "conveyor.il"), folder)
    text = open(os.path.join(src, "conveyor.yaml")).read()
    text += "servers:\n  http:\n    tcp: 127.0.0.1:%d\n    writable: \"%s\"\n" % (http_port, writable)
    path = os.path.join(folder, "conveyor.yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


@pytest.fixture(scope="session")
def artefacts(request):
    """Beside the JUnit file when there is one (catkin's test results), else in the build tree."""
    xml = getattr(request.config.option, "xmlpath", None)
    base = os.path.dirname(os.path.abspath(xml)) if xml else os.path.join(ROOT, ".build")
    path = os.path.join(base, "monitor_page")
    os.makedirs(path, exist_ok=True)
    return path


@pytest.fixture(scope="module")
def scratch():
    path = tempfile.mkdtemp(prefix="plc_cell_browser.")
    yield path
    shutil.rmtree(path, ignore_errors=True)


@pytest.fixture
def browser(request, artefacts, scratch):
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--window-size=1400,1000", "--user-data-dir=%s" % tempfile.mkdtemp(dir=scratch)):
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    driver.set_page_load_timeout(WAIT)
    yield driver
    driver.save_screenshot(os.path.join(artefacts, re.sub(r"\W+", "_", request.node.name) + ".png"))
    driver.quit()


def wait(driver, what, condition, limit=WAIT):
    """condition(driver) truthy within limit, else a failure that says what was awaited.

    The page redraws its panels as the cell's values come: an element a condition found
    may be replaced before it reads it (stale), and that poll is simply not yet true."""
    return WebDriverWait(driver, limit, poll_frequency=0.1, ignored_exceptions=(StaleElementReferenceException,)).until(
        condition, message="waited %.0f s for %s" % (limit, what))


def js(driver, script, *args):
    return driver.execute_script(script, *args)


def open_page(driver, base):
    driver.get(base + "/")
    wait(driver, "the ladder's networks", lambda d: d.find_elements("css selector", "#ladder .net"))
