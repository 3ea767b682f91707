#!/usr/bin/python3
"""The example line on ROS in virtual time (the line nodelet with ~virtual_time: true): driven
by /clock, every cell's signals change at the same instants, to the same values, as in
`plc_cell sim --line` of the same file, run after run (<line>/reset gives a fresh line); a
stamped input is read by its cell's first scan at or after its stamp, one that comes after
that scan is counted on /diagnostics; a cell's own ~reset is
refused, naming the line's."""
import subprocess
import tempfile
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Trigger

from plc_cell.msg import ScanProgress, Signal
from plc_cell.srv import ReadMemory

LINE = "/example_line"
CELLS = ("infeed", "robot", "test")
PERIOD_NS = {"infeed": 1000000, "robot": 1000000, "test": 2000000}
LAG_NS = 100000000  # the nodelet's ~virtual_time_lag: 0.1 s
TIMEOUT = 30.0  # every wait on a message, in wall-clock seconds
RUN_S = 10  # the line's time each run covers: the first part through the test station


def node(cell):
    return "%s/%s/plc_node/" % (LINE, cell)


class Watch(object):
    """Every cell's signals_stamped/<name> and ~virtual_time/scanned, from one run's time 0."""

    def __init__(self):
        self.cond = threading.Condition()
        self.t0_ns = None
        self.changes = {}  # "cell.name" -> [(ns from t0, value)]
        self.received = {}  # topic -> messages from t0 on
        self.progress = {}
        self.subs = []
        topics = [t for t, _ in rospy.get_published_topics() if "/plc_node/signals_stamped/" in t]
        for t in sorted(topics):
            cell = t[len(LINE) + 1:].split("/")[0]
            name = cell + "." + t.rsplit("/", 1)[1]
            self.subs.append(rospy.Subscriber(t, Signal, self._signal, callback_args=(t, name), queue_size=10000))
        for cell in CELLS:
            self.subs.append(rospy.Subscriber(node(cell) + "virtual_time/scanned", ScanProgress, self._progress,
                                              callback_args=cell, queue_size=1000))
        self.wait(lambda: all(s.get_num_connections() > 0 for s in self.subs), "every topic connected")

    def _signal(self, m, args):
        topic, name = args
        with self.cond:
            if self.t0_ns is None or m.header.stamp.to_nsec() < self.t0_ns:
                return  # a latched message, or one of an earlier run
            self.received[topic] = self.received.get(topic, 0) + 1
            self.changes.setdefault(name, []).append((m.header.stamp.to_nsec() - self.t0_ns, int(m.data)))
            self.cond.notify_all()

    def _progress(self, m, cell):
        with self.cond:
            self.progress[cell] = m
            self.cond.notify_all()

    def wait(self, pred, what):
        deadline = time.monotonic() + TIMEOUT
        with self.cond:
            while not pred():
                left = deadline - time.monotonic()
                if left <= 0:
                    raise AssertionError("no %s within %.0f s" % (what, TIMEOUT))
                self.cond.wait(min(left, 0.1))

    def scanned_to(self, t_ns):
        """Every cell reported its last scan at or before t_ns, and every message of it came."""
        for cell in CELLS:
            p = self.progress.get(cell)
            if p is None or p.header.stamp.to_nsec() < self.t0_ns + t_ns - t_ns % PERIOD_NS[cell]:
                return False
            for topic, n in zip(p.topics, p.published):
                if "/signals_stamped/" in topic and self.received.get(topic, 0) < n:
                    return False
        return True


class LineVirtualTimeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("line_virtual_time_test", anonymous=True)
        rospy.wait_for_service(LINE + "/reset", timeout=TIMEOUT)
        cls.clock = rospy.Publisher("/clock", Clock, queue_size=1000)
        cls.watch = Watch()
        cls.t0_ns = 1000 * 10 ** 9  # each run's time 0 after every stamp of the runs before
        cls.line = rospy.get_param("~line")

    def tick(self, t_ns):
        c = Clock()
        c.clock.secs, c.clock.nsecs = divmod(self.t0_ns + t_ns + LAG_NS, 10 ** 9)
        self.clock.publish(c)

    def run_line(self, until_s, inputs=()):
        """A fresh line run to until_s of its time, in 50 ms clock steps; inputs: (cell, name,
        value, t_ns) sent stamped before the step that scans them. The signals' changes."""
        w = self.watch
        with w.cond:
            w.t0_ns = None
            w.changes, w.received = {}, {}
        LineVirtualTimeTest.t0_ns += 1000 * 10 ** 9
        r = rospy.ServiceProxy(LINE + "/reset", Trigger)()
        self.assertTrue(r.success, r.message)
        w.wait(lambda: all(w.progress.get(c) and w.progress[c].scans == 0 for c in CELLS), "progress after the reset")
        with w.cond:
            w.t0_ns = self.t0_ns
        self.wait_for_connection()
        pubs = {}
        for t_ns in range(0, until_s * 10 ** 9 + 1, 50 * 10 ** 6):
            for cell, name, value, at in inputs:
                if t_ns - 50 * 10 ** 6 < at <= t_ns:
                    pub = pubs.get((cell, name)) or rospy.Publisher(node(cell) + "inputs_stamped/" + name, Signal,
                                                                     queue_size=10)
                    pubs[(cell, name)] = pub
                    w.wait(lambda: pub.get_num_connections() > 0, "a subscriber of %s.%s" % (cell, name))
                    m = Signal(data=value)
                    m.header.stamp.secs, m.header.stamp.nsecs = divmod(self.t0_ns + at, 10 ** 9)
                    sent = w.progress[cell].inputs
                    pub.publish(m)
                    w.wait(lambda: w.progress[cell].inputs > sent, "%s acknowledging its input" % cell)
            self.tick(t_ns)
            w.wait(lambda: w.scanned_to(t_ns), "scan at %.3f s complete" % (t_ns / 1e9))
        with w.cond:
            return {k: list(v) for k, v in w.changes.items()}

    def wait_for_connection(self):
        self.watch.wait(lambda: self.clock.get_num_connections() > 0, "the line subscribed to /clock")

    def simulated(self, until_s, names):
        """The same line in plc_cell sim --line: each name's (ns, value) rows."""
        trace = tempfile.mktemp(suffix=".csv")
        subprocess.run(["rosrun", "plc_cell", "plc_cell", "sim", "--line", self.line, "--duration", "%ds" % until_s,
                        "--watch", ",".join(sorted(names)), "--trace", trace], check=True, stdout=subprocess.DEVNULL,
                       timeout=120)
        rows = {}
        with open(trace) as f:
            next(f)
            for line in f:
                t, name, value = line.strip().split(",")
                ns = int(round(float(t) * 1e9))
                if ns <= until_s * 10 ** 9:
                    rows.setdefault(name, []).append((ns, int(value)))
        return rows

    def test_the_line_runs_as_plc_cell_sim_line_run_after_run(self):
        first = self.run_line(RUN_S)
        self.assertIn("test.part_placed", first)
        self.assertEqual(first["test.part_placed"][1], (4342 * 10 ** 6, 1), "the part on the station's table")
        self.assertEqual(first, self.simulated(RUN_S, first.keys()))
        self.assertEqual(self.run_line(RUN_S), first, "a fresh line after <line>/reset ran otherwise")

    def test_a_stamped_input_is_read_by_its_cells_first_scan_at_or_after_its_stamp(self):
        ms = 10 ** 6
        seen = self.run_line(2, inputs=[("infeed", "stop_button", False, 500 * ms),  # a 1 ms cell's scan
                                        ("test", "test_ok", False, 1001 * ms)])      # between a 2 ms cell's
        self.assertEqual(seen["infeed.stop_button"], [(0, 1), (500 * ms, 0)])
        self.assertEqual(seen["test.test_ok"][-1], (1002 * ms, 0))
        self.assertEqual(seen["infeed.line_running"][-1][1], 0, "the stop button did not stop the line")

    def test_a_late_input_is_counted(self):
        self.run_line(1)
        w = self.watch
        pub = rospy.Publisher(node("infeed") + "inputs_stamped/stop_button", Signal, queue_size=10)
        w.wait(lambda: pub.get_num_connections() > 0, "a subscriber of infeed.stop_button")
        m = Signal(data=False)
        m.header.stamp.secs, m.header.stamp.nsecs = divmod(self.t0_ns + 500 * 10 ** 6, 10 ** 9)  # its scan ran
        sent = w.progress["infeed"].inputs
        pub.publish(m)
        w.wait(lambda: w.progress["infeed"].inputs > sent, "infeed acknowledging its input")
        diag = []
        cond = threading.Condition()

        def on_diag(a):
            with cond:
                diag.extend(s for s in a.status if s.name.endswith(": virtual time"))
                cond.notify_all()
        sub = rospy.Subscriber("/diagnostics", DiagnosticArray, on_diag)
        try:
            deadline = time.monotonic() + TIMEOUT
            with cond:
                while not any(s.level == DiagnosticStatus.WARN for s in diag):
                    self.assertLess(time.monotonic(), deadline, "no WARN 'virtual time' status (seen %s)" % diag[-2:])
                    cond.wait(0.1)
            s = next(s for s in diag if s.level == DiagnosticStatus.WARN)
            self.assertEqual(s.message, "inputs arrived after their scan: infeed 1")
            self.assertIn(("late inputs: infeed", "1"), [(v.key, v.value) for v in s.values])
        finally:
            sub.unregister()

    def test_reads_in_flight_while_the_line_resets_are_answered(self):
        # Hostile timing: every cell's ~read called in a loop from three threads while the line
        # is reset again and again; <line>/reset replaces every cell, and no read may reach a
        # cell that is gone (the line node takes its callbacks one at a time in virtual time).
        stop = threading.Event()
        answers, errors = [], []

        def hammer(cell):
            read = rospy.ServiceProxy(node(cell) + "read", ReadMemory)
            while not stop.is_set():
                try:
                    answers.append(read("R0", 1).success)
                except (rospy.ServiceException, rospy.ROSException) as e:
                    errors.append("%s: %s" % (cell, e))
                    return

        threads = [threading.Thread(target=hammer, args=(c,)) for c in CELLS]
        for t in threads:
            t.start()
        try:
            reset = rospy.ServiceProxy(LINE + "/reset", Trigger)
            for k in range(8):
                r = reset()
                self.assertTrue(r.success, "reset %d: %s" % (k, r.message))
        finally:
            stop.set()
            for t in threads:
                t.join(TIMEOUT)
        self.assertEqual(errors, [])
        self.assertGreater(len(answers), 0)
        self.assertTrue(all(answers), "a read refused")

    def test_a_cell_refuses_its_own_reset(self):
        r = rospy.ServiceProxy(node("robot") + "reset", Trigger)()
        self.assertFalse(r.success)
        self.assertIn("call %s/reset for a fresh line" % LINE, r.message)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "line_virtual_time_test", LineVirtualTimeTest)
