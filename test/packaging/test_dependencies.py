"""The install list has one source of truth.

package.xml names every dependency under its rosdep key; rosdep/bookworm.yaml maps each key
to Debian packages; the Makefile's DEB_PACKAGES (written out because a fresh machine has no
Python before it is installed) must be exactly the image of package.xml under that map,
split as DEMO_PACKAGES (the build and run keys, what `make demo` installs) and TEST_PACKAGES.
And package.xml must be complete: every ROS package, Python module, CMake package and tool
that the code, tests, scripts, launch files and docs use is declared."""
import glob
import os
import re
import xml.etree.ElementTree as ET

import yaml

# realpath: run from the workspace, this file is reached through its links to the package.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))


def read(path):
    with open(os.path.join(ROOT, path), encoding="utf-8") as f:
        return f.read()


def files(*patterns):
    out = []
    for p in patterns:
        out += glob.glob(os.path.join(ROOT, p), recursive=True)
    return sorted(f for f in out if "/.build/" not in f and os.path.isfile(f))


ALL_TAGS = ("depend", "build_depend", "exec_depend", "test_depend", "buildtool_depend",
            "build_export_depend", "doc_depend")


def package_keys(tags=ALL_TAGS):
    root = ET.fromstring(read("package.xml"))
    return {e.text.strip() for t in tags for e in root.findall(t)}


def rules():
    return yaml.safe_load(read("rosdep/bookworm.yaml"))


def makefile_list(name):
    text = read("Makefile").replace("\\\n", " ")
    m = re.search(r"^%s\s*:=(.*)$" % name, text, re.M)
    assert m, "Makefile has no %s line" % name
    return m.group(1).split()


def image(keys):
    r = rules()
    return {p for k in keys if k in r for p in r[k]["debian"]["bookworm"]}


def test_every_key_has_a_debian_rule():
    r = rules()
    missing = sorted(k for k in package_keys() if k not in r)
    assert not missing, "package.xml keys with no rule in rosdep/bookworm.yaml: %s" % missing
    for key, rule in r.items():
        pkgs = rule.get("debian", {}).get("bookworm")
        assert pkgs, "rosdep/bookworm.yaml: %s has no debian/bookworm packages" % key


def test_no_rule_is_unused():
    unused = sorted(set(rules()) - package_keys())
    assert not unused, "rules in rosdep/bookworm.yaml that package.xml does not use: %s" % unused


def test_makefile_installs_exactly_what_package_xml_declares():
    wanted = image(package_keys())
    assert makefile_list("DEB_PACKAGES") == ["$(DEMO_PACKAGES)", "$(PLOT_PACKAGES)", "$(TEST_PACKAGES)"]
    have = set(makefile_list("DEMO_PACKAGES")) | set(makefile_list("PLOT_PACKAGES")) | set(makefile_list("TEST_PACKAGES"))
    assert not (wanted - have), "package.xml needs, Makefile lacks: %s" % sorted(wanted - have)
    assert not (have - wanted), "Makefile installs, package.xml does not declare: %s" % sorted(have - wanted)


# Run keys the demo does not use: the plot scripts' (scripts/plot_*.py), in PLOT_PACKAGES.
PLOT_KEYS = {"python3-matplotlib"}


def test_make_demo_installs_the_build_and_run_keys_only():
    # make demo installs DEMO_PACKAGES: what builds and runs the package; the test keys
    # (compilers for the fuzz builds, a browser, test servers) wait for make test.
    run = image(package_keys() - package_keys(("test_depend",)) - PLOT_KEYS)
    demo = set(makefile_list("DEMO_PACKAGES"))
    assert not (run - demo), "make demo would lack: %s" % sorted(run - demo)
    assert not (demo - run), "DEMO_PACKAGES has packages the demo does not use: %s" % sorted(demo - run)
    assert set(makefile_list("PLOT_PACKAGES")) == image(PLOT_KEYS)
    lists = [set(makefile_list(n)) for n in ("DEMO_PACKAGES", "PLOT_PACKAGES", "TEST_PACKAGES")]
    assert sum(len(x) for x in lists) == len(set.union(*lists)), "a package in two lists"


# ---- completeness: what the code uses is declared ------------------------------------

def test_catkin_components_are_declared():
    text = read("CMakeLists.txt")
    m = re.search(r"find_package\(catkin REQUIRED COMPONENTS([^)]*)\)", text)
    used = set(m.group(1).split())
    missing = sorted(used - package_keys())
    assert not missing, "CMakeLists.txt finds catkin components package.xml lacks: %s" % missing


def test_message_dependencies_are_declared():
    used = set()
    for f in files("msg/*.msg", "srv/*.srv", "action/*.action"):
        for line in open(f, encoding="utf-8"):
            line = line.split("#")[0].strip()
            m = re.match(r"([A-Za-z_][\w]*)/\w+", line)
            if m:
                used.add(m.group(1))
    used.discard("plc_cell")
    used |= {"std_msgs"} if any("Header" in open(f).read() for f in files("msg/*.msg")) else set()
    missing = sorted(used - package_keys())
    assert not missing, "msg/srv/action types from packages package.xml lacks: %s" % missing


# Python modules that come from a key other than their own name.
PY_MODULE_KEYS = {"serial": "python3-serial", "pymodbus": "python3-pymodbus",
                  "matplotlib": "python3-matplotlib", "yaml": None, "pytest": "python3-pytest",
                  "rospkg": None, "genpy": None, "rosgraph": None, "roslib": None}


def test_python_imports_are_declared():
    keys = package_keys()
    problems = []
    for f in files("scripts/**/*.py", "test/**/*.py", "src/**/*.py"):
        for n, line in enumerate(open(f, encoding="utf-8"), 1):
            m = re.match(r"\s*(?:from|import)\s+([A-Za-z_]\w*)", line)
            if not m:
                continue
            mod = m.group(1)
            if mod in PY_MODULE_KEYS:
                key = PY_MODULE_KEYS[mod]
            elif mod.endswith("_msgs") or mod.endswith("_srvs") or mod in (
                    "rospy", "rosbag", "rostest", "actionlib", "rosunit"):
                key = "rostest" if mod == "rosunit" else mod
            else:
                continue
            if key and key not in keys:
                problems.append("%s:%d imports %s: package.xml lacks %s"
                                % (os.path.relpath(f, ROOT), n, mod, key))
    assert not problems, "\n".join(problems)


# Tools run by launch files, tests, scripts, the Makefile and the docs, and their keys.
TOOLS = {"socat": "socat", "mbpoll": "mbpoll", "rosrun": "rosbash", "roscd": "rosbash",
         "rostopic": "rostopic", "rosservice": "rosservice", "roslaunch": "roslaunch",
         "roscore": "roslaunch", "rosbag": "rosbag", "rosnode": "rosnode", "rosmsg": "rosmsg",
         "rostest": "rostest", "clang\\+\\+": "clang", "catkin_make": "catkin", "git": "git",
         "readelf": "build-essential",  # binutils (readelf, nm) comes with build-essential
         "chromium-headless-shell": "chromium-headless-shell", "ctags": "universal-ctags"}


def test_tools_are_declared():
    keys = package_keys()
    problems = []
    sources = files("test/**/*", "scripts/**/*", "launch/**/*", "docs/**/*.md", "README.md",
                    "Makefile", "cmake/**/*.cmake", "CMakeLists.txt")
    for f in sources:
        if os.path.samefile(f, __file__):
            continue
        try:
            text = open(f, encoding="utf-8").read()
        except UnicodeDecodeError:
            continue
        for tool, key in TOOLS.items():
            if key not in keys and re.search(r"(?<![\w/.-])%s(?![\w-])" % tool, text):
                problems.append("%s uses %s: package.xml lacks %s"
                                % (os.path.relpath(f, ROOT), tool.replace("\\", ""), key))
    assert not problems, "\n".join(problems)


# CMake packages found by the build, and the keys that provide them.
CMAKE_PACKAGES = {"yaml-cpp": "yaml-cpp", "ZLIB": "zlib", "benchmark": "benchmark",
                  "PkgConfig": "pkg-config", "GTest": "gtest", "rostest": "rostest", "catkin": "catkin",
                  "asmjit": "libasmjit-dev", "nodelet": "nodelet", "pluginlib": "pluginlib",
                  "Boost": "boost", "nlohmann_json": "nlohmann-json3-dev"}


def test_cmake_packages_are_declared():
    keys = package_keys()
    problems = []
    for f in files("CMakeLists.txt", "cmake/**/*.cmake", "test/**/CMakeLists.txt"):
        text = open(f, encoding="utf-8").read()
        for pkg in re.findall(r"find_package\((\S+)", text):
            key = CMAKE_PACKAGES.get(pkg)
            if key is None:
                problems.append("%s finds %s, which this test does not know: add it to CMAKE_PACKAGES"
                                % (os.path.relpath(f, ROOT), pkg))
            elif key not in keys:
                problems.append("%s finds %s: package.xml lacks %s" % (os.path.relpath(f, ROOT), pkg, key))
        for mod in re.findall(r"pkg_check_modules\(\w+ (?:REQUIRED )?(?:IMPORTED_TARGET )?(\S+)\)", text):
            if mod == "libmodbus" and "libmodbus-dev" not in keys:
                problems.append("%s needs libmodbus: package.xml lacks libmodbus-dev" % f)
    assert not problems, "\n".join(problems)


def test_message_packages_bring_their_definitions():
    # Debian splits a message package three ways: ros-X (the .msg files that message
    # generation and rosmsg read), libX-dev (C++ headers) and python3-X. The headers do not
    # pull the definitions in, so a fresh machine without ros-std-msgs cannot generate
    # plc_cell's messages ("Cannot locate message [Header] in package [std_msgs]").
    r = rules()
    missing = []
    for key in sorted(package_keys()):
        if key.endswith("_msgs") or key.endswith("_srvs"):
            pkgs = r[key]["debian"]["bookworm"]
            for want in ("ros-" + key.replace("_", "-"), "python3-" + key.replace("_", "-")):
                if want not in pkgs:
                    missing.append("%s: %s" % (key, want))
    assert not missing, "message keys without their definitions or Python modules: %s" % missing


def test_python_scripts_run_on_debians_python():
    # rospy and the message modules exist for Debian's /usr/bin/python3 only; a script that
    # asks env for python3 gets a pyenv interpreter first on PATH, and its node dies on import.
    bad = []
    for f in files("test/**/*.py", "scripts/**/*.py"):
        with open(f, encoding="utf-8") as fh:
            first = fh.readline()
        if first.startswith("#!") and first.strip() != "#!/usr/bin/python3":
            bad.append("%s: %s" % (os.path.relpath(f, ROOT), first.strip()))
    assert not bad, "\n".join(bad)
