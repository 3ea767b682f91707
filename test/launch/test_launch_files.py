"""The launch files are safe and predictable with no arguments:
* nothing points at a serial device or an address off this machine by default;
* cell_sim.launch leaves the cell YAML's scan period alone unless scan_period is given;
* in cells.launch a cell that dies is restarted alone: respawn, and never required
  (a required node's death would stop every other cell)."""
import os
import re

import roslaunch.config
import yaml

# realpath: run from the workspace, this file is reached through its links to the package.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
LAUNCH = os.path.join(ROOT, "launch")


def load(name, *args):
    path = os.path.join(LAUNCH, name)
    return roslaunch.config.load_config_default([(path, list(args)) if args else path], None, verbose=False)


def loopback(hostport):
    host = hostport.rsplit(":", 1)[0]
    return host in ("127.0.0.1", "localhost", "::1", "[::1]") or host.startswith("127.")


def test_no_default_points_off_this_machine():
    for name in sorted(os.listdir(LAUNCH)):
        cfg = load(name)
        for key, p in cfg.params.items():
            v = str(p.value)
            assert "/dev/tty" not in v, "%s: %s = %s opens a serial device by default" % (name, key, v)
            for ip in re.findall(r"\b\d+\.\d+\.\d+\.\d+\b", v):
                assert ip.startswith("127."), "%s: %s = %s points off this machine" % (name, key, v)


def test_modbus_bridge_default_polls_loopback_only():
    cfg = load("modbus_bridge.launch")
    path = cfg.params["/modbus_bridge/config"].value
    with open(path) as f:
        devices = yaml.safe_load(f)["devices"]
    assert devices
    for d in devices:
        assert "rtu" not in d, "%s: a serial device by default" % d["name"]
        assert loopback(d["tcp"]), d["tcp"]


def test_fatek_bridge_default_is_the_local_soft_plc():
    cfg = load("fatek_bridge.launch")
    assert cfg.params["/fatek_bridge/tcp"].value == "127.0.0.1:5000"
    assert "/fatek_bridge/port" not in cfg.params
    serial = load("fatek_bridge.launch", "port:=/dev/ttyUSB0")
    assert serial.params["/fatek_bridge/port"].value == "/dev/ttyUSB0"
    assert "/fatek_bridge/tcp" not in serial.params


def test_tri_bridge_default_is_the_local_soft_plc():
    cfg = load("tri_bridge.launch")
    assert cfg.params["/tri_bridge/tcp"].value == "127.0.0.1:9080"
    assert "/tri_bridge/port" not in cfg.params
    assert cfg.params["/tri_bridge/baud"].value == 38400
    # The demo cell's points, so the bare launch shows plc_node's signal names.
    assert cfg.params["/tri_bridge/config"].value.endswith("/examples/tri/conveyor.yaml")
    serial = load("tri_bridge.launch", "port:=/dev/ttyUSB0")
    assert serial.params["/tri_bridge/port"].value == "/dev/ttyUSB0"
    assert "/tri_bridge/tcp" not in serial.params


def test_cell_sim_keeps_the_cells_scan_period():
    cfg = load("cell_sim.launch", "cell:=%s/examples/oven/oven.yaml" % ROOT)
    assert "/plc_node/scan_period" not in cfg.params, "the launch file overrides oven.yaml's 0.01 s"
    given = load("cell_sim.launch", "scan_period:=0.005")
    assert given.params["/plc_node/scan_period"].value == 0.005
    assert "/plc_node/modbus_tcp" not in cfg.params and "/plc_node/fatek_tcp" not in cfg.params
    assert "/plc_node/tri_tcp" not in cfg.params
    served = load("cell_sim.launch", "tri_tcp:=127.0.0.1:9080")
    assert served.params["/plc_node/tri_tcp"].value == "127.0.0.1:9080"


def test_cells_restart_alone():
    cfg = load("cells.launch")
    nodes = [n for n in cfg.nodes if n.type == "plc_node"]
    assert len(nodes) == 2
    for n in nodes:
        assert n.respawn, "%s/%s is not respawned" % (n.namespace, n.name)
        assert not n.required, "%s/%s is required: its crash stops the other cells" % (n.namespace, n.name)
    assert not any(k.endswith("/persist_file") or k.endswith("/modbus_tcp") for k in cfg.params), \
        "empty arguments must not override the cell YAML's servers or store"


def test_no_argument_is_listed_as_required():
    """`roslaunch ... --ros-args` lists an argument with an empty default under "Required
    Arguments": every argument of the launch files has a default (and a doc line)."""
    import roslaunch.arg_dump
    for name in sorted(os.listdir(LAUNCH)):
        if not name.endswith(".launch"):
            continue
        for arg, (doc, default) in roslaunch.arg_dump.get_args([os.path.join(LAUNCH, name)]).items():
            assert default, "%s: %s would be listed as required" % (name, arg)
            assert doc, "%s: %s is undocumented" % (name, arg)


def test_scan_period_help_names_the_yaml_key():
    import roslaunch.arg_dump
    for name in ("cell_sim.launch", "cells.launch"):
        doc = roslaunch.arg_dump.get_args([os.path.join(LAUNCH, name)])["scan_period"][0]
        assert "plc.scan_period" in doc, "%s: %s" % (name, doc)


def test_cells_pass_only_what_is_given():
    cfg = load("cells.launch")
    assert not any(k.endswith(("/persist_file", "/modbus_tcp", "/fatek_tcp", "/scan_period")) for k in cfg.params)
    given = load("cells.launch", "scan_period:=0.005", "b_persist:=/tmp/b.bin", "a_fatek_tcp:=127.0.0.1:5001")
    assert given.params["/cell_a/plc_node/scan_period"].value == 0.005
    assert given.params["/cell_b/plc_node/scan_period"].value == 0.005
    assert given.params["/cell_b/plc_node/persist_file"].value == "/tmp/b.bin"
    assert "/cell_a/plc_node/persist_file" not in given.params
    assert given.params["/cell_a/plc_node/fatek_tcp"].value == "127.0.0.1:5001"
    assert "/cell_b/plc_node/fatek_tcp" not in given.params


def test_cell_sim_passes_only_what_is_given():
    cfg = load("cell_sim.launch")
    assert "/plc_node/program" not in cfg.params
    given = load("cell_sim.launch", "program:=/tmp/p.il")
    assert given.params["/plc_node/program"].value == "/tmp/p.il"


def test_many_cells_loads_each_cell_into_one_manager():
    cfg = load("many_cells.launch", "cells:=5", "scan_period:=0.001")
    managers = [n for n in cfg.nodes if n.args.strip() == "manager"]
    assert [m.name for m in managers] == ["cells"]
    loads = sorted((n.namespace + n.name, n.args.split()) for n in cfg.nodes if n.args.startswith("load"))
    assert loads == [("/cell_%d/plc_node" % i, ["load", "plc_cell/PlcNodelet", "/cells"]) for i in range(5)]
    for i in range(5):
        assert cfg.params["/cell_%d/plc_node/scan_period" % i].value == 0.001
        assert cfg.params["/cell_%d/plc_node/shared_scan" % i].value is True
        assert cfg.params["/cell_%d/plc_node/rt_priority" % i].value == 0
    assert "/cell_5/plc_node/cell" not in cfg.params


def test_many_cells_passes_the_rt_priority_to_every_cell():
    cfg = load("many_cells.launch", "cells:=3", "rt_priority:=50", "shared_scan_threads:=2")
    for i in range(3):
        assert cfg.params["/cell_%d/plc_node/rt_priority" % i].value == 50
        assert cfg.params["/cell_%d/plc_node/shared_scan_threads" % i].value == 2
