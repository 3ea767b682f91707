"""The layers of docs/architecture.md, checked two ways: no source of a layer includes a
header of a layer above it, and no built library of a layer needs a library above it
(the core library needs none of the package's)."""
import os
import re
import subprocess

import pytest

# realpath: run from the workspace, this file is reached through its links to the package.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
LIB_DIR = os.environ.get("PLC_CELL_LIB_DIR", os.path.join(ROOT, ".build", "ws", "devel", "lib"))

# What each folder of src/ (and include/plc_cell/) may include besides itself. The order is
# the layering: a folder reaches only folders listed before it.
BELOW = {
    "core": set(),
    "io": {"core"},
    "config": {"core", "io"},
    "timeline": {"core"},
    "coverage": {"core"},
    "hsc": {"core", "io", "config", "timeline"},
    "temp": {"core", "io", "config"},
    "motion": {"core", "io", "config", "timeline", "hsc"},
    "sim": {"core", "io", "config", "timeline", "hsc", "temp", "motion"},
    "persist": {"core", "io", "config"},
    "fatek": {"core", "io", "config"},
    "tri": {"core", "io", "config"},
    # The TRi map profile of the Modbus slave reads the TRi memory map.
    "modbus": {"core", "io", "config", "tri"},
    # FUN150/151: the cell's ports reach both protocol masters.
    "comm": {"core", "io", "config", "fatek", "modbus", "tri"},
    # The composition root: the Cell sits on every library layer.
    "runtime": {"core", "io", "config", "timeline", "hsc", "temp", "motion", "sim", "persist", "fatek", "modbus", "tri", "comm"},
    # Scenario tests run cases on fresh cells: they sit on the composition root.
    "scenario": {"core", "io", "config", "timeline", "hsc", "temp", "motion", "sim", "persist", "fatek", "modbus",
                 "tri", "comm", "runtime"},
    # Exploration and mutation testing run scenario cases on fresh cells.
    "explore": {"core", "io", "config", "timeline", "hsc", "temp", "motion", "sim", "persist", "fatek", "modbus",
                "tri", "comm", "runtime", "scenario"},
    "mutation": {"core", "io", "config", "timeline", "coverage", "hsc", "temp", "motion", "sim", "persist", "fatek",
                 "modbus", "tri", "comm", "runtime", "scenario"},
    "cli": None,  # the tool and the nodes sit on top and may use any layer
    "ros": None,
}
# The shared libraries of the layers (the protocol libraries are static: the include
# check covers them).
LIBS = ["core", "io", "config", "timeline", "coverage", "hsc", "temp", "motion", "sim"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"plc_cell/(\w+)/')


def sources():
    for top, layer_at in (("src", 1), (os.path.join("include", "plc_cell"), 2)):
        for d, _, files in os.walk(os.path.join(ROOT, top)):
            for f in files:
                path = os.path.relpath(os.path.join(d, f), ROOT)
                yield path, path.split(os.sep)[layer_at]


def test_every_folder_has_a_place_in_the_layering():
    assert {layer for _, layer in sources()} <= set(BELOW)


def test_no_layer_includes_a_layer_above_it():
    bad = []
    for path, layer in sources():
        allowed = BELOW[layer]
        if allowed is None:
            continue
        with open(os.path.join(ROOT, path), errors="replace") as f:
            for n, line in enumerate(f, 1):
                m = INCLUDE.match(line)
                if m and m.group(1) != layer and m.group(1) not in allowed:
                    bad.append("%s:%d: layer %s includes plc_cell/%s" % (path, n, layer, m.group(1)))
    assert not bad, "\n".join(bad)


def needed(lib):
    path = os.path.join(LIB_DIR, "libplc_cell_%s.so" % lib)
    if not os.path.exists(path):
        pytest.fail("%s is not built (run make build)" % path)
    out = subprocess.run(["readelf", "-d", path], stdout=subprocess.PIPE, universal_newlines=True, check=True).stdout
    return {m.group(1) for m in re.finditer(r"\(NEEDED\).*\[libplc_cell_(\w+)\.so\]", out)}


@pytest.mark.parametrize("lib", LIBS)
def test_each_library_needs_only_the_layers_below(lib):
    assert needed(lib) <= BELOW[lib], "libplc_cell_%s.so needs %s" % (lib, sorted(needed(lib) - BELOW[lib]))


def test_the_core_library_needs_nothing_of_the_package():
    assert needed("core") == set()
    # ...and leaves nothing of the package unresolved: every plc_cell symbol it uses is its own.
    out = subprocess.run(["nm", "-D", "-C", "--undefined-only", os.path.join(LIB_DIR, "libplc_cell_core.so")],
                         stdout=subprocess.PIPE, universal_newlines=True, check=True).stdout
    assert "plc_cell::" not in out, out
