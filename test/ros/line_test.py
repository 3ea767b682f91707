#!/usr/bin/python3
"""The example line on ROS: each cell a plc_node under /example_line/<cell>/plc_node/, and a
part carried by the wires from the infeed through the robot to the test station, in one
nodelet manager (~split false: no wire on a topic) or split over two (~split true: the
robot's zone handshake with the test station crosses on /example_line/wires/<index>).
Bad input: a line nodelet with an unknown cell or a broken line file is refused with the
error where it lies; the scenario_runner refuses a line's scenario naming a cell the line has
not, or one not running on ROS, at its file:line, and a line running in real time in virtual
time; the line nodelet refuses ~virtual_time of another type than a bool (and a lag that is not a
number), and a split line in
virtual time naming a wire that crosses."""
import os
import random
import subprocess
import tempfile
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from nodelet.srv import NodeletLoad, NodeletUnload
from rosgraph_msgs.msg import Log
from std_msgs.msg import Bool
from std_srvs.srv import Trigger

from plc_cell.msg import WireSample
from plc_cell.srv import ReadMemory

LINE = "/example_line/"
CELLS = ("infeed", "robot", "test")
# The first part enters at 1 s of the line's time and is on the test station's table at
# 4.342 s (docs/lines.md, "The example line"); the rest is the processes' start.
TIMEOUT = 60.0
# The wires of examples/line/line.line.yaml between the robot and the test station.
CROSSING = {4: "robot.zone_request -> test.robot_request", 5: "robot.in_zone -> test.robot_in_zone",
            6: "test.robot_grant -> robot.zone_grant", 7: "robot.part_placed -> test.part_placed"}


def node(cell):
    return LINE + cell + "/plc_node/"


class Seen(object):
    """Every value a topic carried, in order (a pulse shorter than a test's wait is kept)."""

    def __init__(self, topic, msg_type, value=lambda m: m.data):
        self.values = []
        self.cond = threading.Condition()
        self.value = value
        self.sub = rospy.Subscriber(topic, msg_type, self._cb)
        self.topic = topic

    def _cb(self, msg):
        with self.cond:
            self.values.append(self.value(msg))
            self.cond.notify_all()

    def wait_for(self, pred, what, timeout=TIMEOUT):
        deadline = time.monotonic() + timeout
        with self.cond:
            while not any(pred(v) for v in self.values):
                left = deadline - time.monotonic()
                if left <= 0:
                    raise AssertionError("%s: no %s within %.0f s (seen %s)" % (self.topic, what, timeout, self.values[-5:]))
                self.cond.wait(left)


class LineTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("line_test", anonymous=True)
        cls.split = rospy.get_param("~split", False)
        for cell in CELLS:
            rospy.wait_for_service(node(cell) + "read", timeout=TIMEOUT)

    def read(self, cell, address):
        return list(rospy.ServiceProxy(node(cell) + "read", ReadMemory)(address, 1).values)[0]

    def test_a_part_goes_through_the_line(self):
        """Each wired input of the chain sees its source: through the process or across."""
        line_on = Seen(node("robot") + "signals/line_on", Bool)
        nest = Seen(node("robot") + "signals/nest_sensor", Bool)
        placed = Seen(node("test") + "signals/part_placed", Bool)
        granted = Seen(node("robot") + "signals/zone_grant", Bool)
        line_on.wait_for(lambda v: v, "line_on ON (infeed.line_running's wire)")
        nest.wait_for(lambda v: v, "nest_sensor ON (the part released by the infeed)")
        granted.wait_for(lambda v: v, "zone_grant ON (the test station's grant)")
        placed.wait_for(lambda v: v, "part_placed ON (the robot's placed signal)")
        deadline = time.monotonic() + TIMEOUT
        while self.read("test", "R0") < 1:  # parts the station received (its program's count)
            self.assertLess(time.monotonic(), deadline, "test.R0: no part received within %.0f s" % TIMEOUT)
            rospy.sleep(0.05)
        self.assertGreaterEqual(self.read("robot", "R1"), 1, "robot.R1: the robot placed no part")

    def test_wires_on_topics_only_across_processes(self):
        topics = dict(rospy.get_published_topics())
        wires = sorted(t for t in topics if t.startswith(LINE + "wires/"))
        if not self.split:
            self.assertEqual(wires, [], "one process carries its wires itself")
            return
        self.assertEqual(wires, sorted(LINE + "wires/%d" % w for w in CROSSING))
        for w, text in CROSSING.items():
            m = rospy.wait_for_message(LINE + "wires/%d" % w, WireSample, timeout=TIMEOUT)  # latched
            self.assertEqual(m.wire, text)

    def test_a_cell_of_a_line_refuses_reset(self):
        r = rospy.ServiceProxy(node("robot") + "reset", Trigger)()
        self.assertFalse(r.success)
        self.assertIn("part of a line", r.message)

    def wires_status(self, name_end, pred, what):
        """The first /diagnostics status whose name ends with name_end and for which pred holds."""
        diag = Seen("/diagnostics", DiagnosticArray, value=lambda m: [s for s in m.status if s.name.endswith(name_end)])
        diag.wait_for(lambda statuses: any(pred(s) for s in statuses), what, timeout=TIMEOUT)
        return next(s for v in diag.values for s in v if pred(s))

    def test_wires_on_diagnostics(self):
        """Each process says how many of its wires cross, and that each has its other end."""
        # Split: the robot's zone request, in-zone and placed signals leave, its grant arrives.
        counts = ["3 leaving, 1 arriving", "1 leaving, 3 arriving"] if self.split else ["0 leaving, 0 arriving"]
        for c in counts:
            s = self.wires_status(": wires", lambda s: s.message == c, "wires status '%s'" % c)
            self.assertEqual(s.level, DiagnosticStatus.OK)
            self.assertEqual(s.hardware_id, "plc_cell/line/example_line")

    def load_station_alone(self, name):
        """The test station alone, as the line nodelet /NAME (in a namespace where no process
        runs the robot); unloaded by the caller."""
        manager = rospy.get_param("~manager")
        rospy.set_param("%s/line" % name, rospy.get_param("~line"))
        rospy.set_param("%s/cells" % name, "test")
        load = rospy.ServiceProxy("/%s/load_nodelet" % manager, NodeletLoad)
        load.wait_for_service(timeout=TIMEOUT)
        self.assertTrue(load(name=name, type="plc_cell/LineNodelet", remap_source_args=[], remap_target_args=[],
                             my_argv=[], bond_id="").success)
        return lambda: rospy.ServiceProxy("/%s/unload_nodelet" % manager, NodeletUnload)(name=name)

    def test_a_wire_whose_source_runs_nowhere_is_an_error(self):
        unload = self.load_station_alone("/elsewhere/lonely")
        try:
            expected = ("wire 7 (robot.part_placed -> test.part_placed): no process publishes "
                        "/elsewhere/example_line/wires/7: test.part_placed holds the last value it got")
            s = self.wires_status("lonely: wires", lambda s: s.level == DiagnosticStatus.ERROR, "ERROR status")
            self.assertIn(expected, s.message)
        finally:
            unload()

    def test_a_wire_of_another_line_file_is_refused(self):
        """A process whose wire 7 is another wire: none of its values is taken, and it is said."""
        unload = self.load_station_alone("/other/station")
        try:
            read = rospy.ServiceProxy("/other/example_line/test/plc_node/read", ReadMemory)
            read.wait_for_service(timeout=TIMEOUT)
            pub = rospy.Publisher("/other/example_line/wires/7", WireSample, queue_size=10, latch=True)
            random.seed(7)  # hostile samples: other wires' texts, any value
            for _ in range(20):
                pub.publish(WireSample(wire=random.choice(["robot.in_zone -> test.part_placed", "",
                                                          "robot.part_placed -> test.robot_request",
                                                          "robot.part_placed->test.part_placed"]),
                                       source_us=random.getrandbits(64), value=random.getrandbits(32) | 1))
            s = self.wires_status("station: wires", lambda s: s.level == DiagnosticStatus.ERROR and
                                  "carries another wire" in s.message, "ERROR 'carries another wire'")
            self.assertIn("wire 7 (robot.part_placed -> test.part_placed): /other/example_line/wires/7 carries "
                          "another wire (another line file)", s.message)
            self.assertEqual(list(read("part_placed", 1).values), [0], "a refused sample drove the input")
            # The wire's own samples still arrive.
            pub.publish(WireSample(wire=CROSSING[7], source_us=0, value=1))
            deadline = time.monotonic() + TIMEOUT
            while list(read("part_placed", 1).values) != [1]:
                self.assertLess(time.monotonic(), deadline, "test.part_placed: the wire's sample not taken")
                rospy.sleep(0.01)
        finally:
            unload()

    def refused(self, name, params, expected):
        """A line nodelet loaded with params fails to load, saying expected on /rosout."""
        # Connected to every node that logs (the manager among them) before the load: rostest
        # runs no rosout node, and a message published before a connection is lost.
        said = Seen("/rosout", Log, value=lambda m: (m.level, m.msg))
        deadline = time.monotonic() + TIMEOUT
        while True:
            pubs = [p for t, p in rospy.get_master().getSystemState()[2][0] if t == "/rosout"]
            if pubs and said.sub.get_num_connections() >= len(pubs[0]):
                break
            self.assertLess(time.monotonic(), deadline, "/rosout: not connected to %s within %.0f s" % (pubs, TIMEOUT))
            rospy.sleep(0.01)
        for k, v in params.items():
            rospy.set_param("/%s/%s" % (name, k), v)
        manager = rospy.get_param("~manager")
        load = rospy.ServiceProxy("/%s/load_nodelet" % manager, NodeletLoad)
        load.wait_for_service(timeout=TIMEOUT)
        try:  # the manager answers a nodelet that threw with a failed call
            loaded = load(name="/" + name, type="plc_cell/LineNodelet", remap_source_args=[], remap_target_args=[],
                          my_argv=[], bond_id="").success
        except rospy.ServiceException:
            loaded = False
        self.assertFalse(loaded, "the manager loaded a line nodelet with %s" % params)
        said.wait_for(lambda v: v[0] == Log.FATAL and expected in v[1], "FATAL '%s'" % expected, timeout=10)
        self.read("robot", "R1")  # the manager and its line go on: a ServiceException if not

    def test_an_unknown_cell_is_refused(self):
        line = rospy.get_param("~line")
        self.refused("bad_cells", {"line": line, "cells": "robot,press"},
                     "~cells: line example_line has no cell 'press' to build here (infeed, robot, test)")

    def test_a_broken_line_file_is_refused_at_its_line(self):
        d = tempfile.mkdtemp()
        path = os.path.join(d, "broken.line.yaml")
        example = os.path.dirname(rospy.get_param("~line"))
        wire = "  - {from: robot.ready, to: press.X20}"
        with open(path, "w") as f:
            f.write("cells:\n  robot: %s/robot.yaml\nwires:\n%s\n" % (example, wire))
        self.refused("bad_file", {"line": path},
                     "%s:4:%d: error: 'press.X20': no cell 'press' in the line" % (path, wire.index("press") + 1))

    def test_a_split_line_is_refused_in_virtual_time_naming_the_wire(self):
        self.refused("vt_split", {"line": rospy.get_param("~line"), "cells": "test", "virtual_time": True},
                     "~virtual_time: wire 4 (robot.zone_request -> test.robot_request) joins a cell here to the cell "
                     "'robot' of another process: a line split over processes runs on ROS in real time only")

    def test_virtual_time_of_another_type_is_refused(self):
        line = rospy.get_param("~line")
        for value, said in (("yes", "the string 'yes'"), (1, "the number 1"), ([True], "a list or a mapping")):
            self.refused("vt_type", {"line": line, "virtual_time": value},
                         "~virtual_time: true or false, not %s" % said)
        self.refused("vt_lag", {"line": line, "virtual_time": True, "virtual_time_lag": "soon"},
                     "~virtual_time_lag: a number of seconds in [0, 60]")

    def run_runner(self, scenario, **params):
        """The scenario_runner on scenario with params, to its end: its exit status and output."""
        args = ["rosrun", "plc_cell", "scenario_runner", "_scenario:=" + scenario]
        args += ["_%s:=%s" % kv for kv in sorted(params.items())]
        p = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                           timeout=60)
        return p.returncode, p.stdout

    def test_the_scenario_runner_refuses_names_it_cannot_reach_at_their_line(self):
        d = tempfile.mkdtemp()
        path = os.path.join(d, "names.scenario.yaml")
        with open(path, "w") as f:
            f.write("line: %s\nhardware: true\ncases:\n  - name: a\n    steps:\n"
                    "      - expect: press.X0\n"           # line 6: no such cell
                    "      - force: {robot.ready: on}\n"   # line 7: on ROS here, nowhere under /elsewhere
                    % rospy.get_param("~line"))
        rc, out = self.run_runner(path, real_time="true", timeout="2")
        self.assertNotEqual(rc, 0, out)
        self.assertIn("refused on ros:/example_line, nothing was written", out)
        self.assertIn(path + ":6: error: key 'expect': 'press.X0': no cell 'press' in the line (infeed, robot, test)",
                      out)
        self.assertNotIn(path + ":7:", out)
        rc, out = self.run_runner(path, real_time="true", timeout="1", line_ns="/elsewhere")
        self.assertNotEqual(rc, 0, out)
        self.assertIn(path + ":7: error: key 'force': 'robot.ready': the cell 'robot' of the line is not running on "
                      "ROS (no parameter /elsewhere/robot/plc_node/cell", out)
        rc, out = self.run_runner(path)  # in virtual time, on a line in real time
        self.assertNotEqual(rc, 0, out)
        self.assertIn("/example_line/infeed/plc_node runs in real time: a line's scenario in virtual time needs the "
                      "line nodelet's ~virtual_time: true (or give the runner ~real_time: true)", out)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "line_test", LineTest)
