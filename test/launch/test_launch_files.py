"""The launch files are safe and predictable with no arguments:
* nothing points at a serial device or an address off this machine by default;
* cell_sim.launch leaves the cell YAML's scan period alone unless scan_period is given;
* in cells.launch a cell that dies is restarted alone: respawn, and never required
  (a required node's death would stop every other cell)."""
import os
import re

import roslaunch.config
import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
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
