"""The layers of docs/architecture.md, checked two ways: the compiler refuses an upward
include (each layer's library compiles against an include root that holds only the layers it
may use, cmake/layers.cmake), and no built library of a layer needs a library above it (the
core library needs none of the package's)."""
import os
import re
import subprocess
import tempfile

import pytest

# realpath: run from the workspace, this file is reached through its links to the package.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
LIB_DIR = os.environ.get("PLC_CELL_LIB_DIR", os.path.join(ROOT, ".build", "ws", "devel", "lib"))
BUILD_DIR = os.environ.get("PLC_CELL_BUILD_DIR", os.path.join(ROOT, ".build", "ws", "build", "plc_cell"))
ROOTS_DIR = os.path.join(BUILD_DIR, "layer_includes")


def rules():
    """cmake/layers.cmake's table: layer -> the layers it may use besides itself."""
    text = open(os.path.join(ROOT, "cmake", "layers.cmake"), encoding="utf-8").read()
    table = re.search(r"set\(PLC_CELL_LAYER_RULES(.*?)\)", text, re.S).group(1)
    out = {}
    for rule in re.findall(r'"([^"]*)"', table):
        layer, *below = rule.split()
        out[layer] = set(below)
    return out


BELOW = rules()
TOP = {"cli", "ros"}  # the tool and the nodes sit on top and may use any layer
# The shared libraries of the layers (the protocol libraries are static: the include roots
# cover them).
LIBS = ["core", "io", "config", "timeline", "coverage", "ladder", "hsc", "temp", "motion", "sim"]


def folders():
    for top in ("src", os.path.join("include", "plc_cell")):
        for name in os.listdir(os.path.join(ROOT, top)):
            if os.path.isdir(os.path.join(ROOT, top, name)):
                yield os.path.join(top, name), name


def test_every_folder_has_a_place_in_the_layering():
    stray = sorted(path for path, layer in folders() if layer not in BELOW and layer not in TOP)
    assert not stray, "folders with no rule in cmake/layers.cmake: %s" % stray


def test_the_table_keeps_the_layering_acyclic_and_transitive():
    # A layer may use what the layers it uses may use; a cycle would make "above" meaningless.
    for layer, below in BELOW.items():
        assert layer not in below
        for b in below:
            assert BELOW[b] <= below, "%s uses %s, which uses %s" % (layer, b, sorted(BELOW[b] - below))


def a_header(layer):
    d = os.path.join(ROOT, "include", "plc_cell", layer)
    return "plc_cell/%s/%s" % (layer, sorted(f for f in os.listdir(d) if f.endswith(".h"))[0])


def compile_flags(layer):
    """The compiler and the include directories of the layer's library, as CMake gives them."""
    path = os.path.join(ROOTS_DIR, layer + ".dirs")
    if not os.path.exists(path):
        pytest.fail("%s is not generated (run make build)" % path)
    compiler, *dirs = [line for line in open(path).read().splitlines() if line]
    return compiler, ["-I" + d for d in dirs]


def preprocess(layer, includes):
    compiler, flags = compile_flags(layer)
    with tempfile.NamedTemporaryFile("w", suffix=".cpp") as src:
        src.write("".join('#include "%s"\n' % h for h in includes))
        src.flush()
        return subprocess.run([compiler, "-std=c++17", "-E", "-o", os.devnull] + flags + [src.name],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                              env=dict(os.environ, LC_ALL="C"))


@pytest.mark.parametrize("layer", sorted(BELOW))
def test_a_layer_compiles_against_the_layers_it_may_use(layer):
    headers = [a_header(h) for h in sorted(BELOW[layer] | {layer})]
    run = preprocess(layer, headers)
    assert run.returncode == 0, run.stdout


@pytest.mark.parametrize("layer", sorted(BELOW))
def test_an_upward_include_does_not_compile(layer):
    # A source including a header of each layer the layer may not use: with the include
    # directories the layer's library is built with, every one is refused.
    accepted = []
    for other in sorted(set(BELOW) - BELOW[layer] - {layer}):
        run = preprocess(layer, [a_header(other)])
        if run.returncode == 0 or "No such file" not in run.stdout:
            accepted.append("%s: %s" % (a_header(other), run.stdout.strip()[:200] or "accepted"))
    assert not accepted, "layer %s may include:\n%s" % (layer, "\n".join(accepted))


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
