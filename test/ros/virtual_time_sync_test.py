#!/usr/bin/python3
"""rostest: in virtual time, ~virtual_time/scanned counts every message plc_node published
on each topic, so a driver that has received that many has the whole scan; a stamped input
is acknowledged there; ~reset gives a fresh cell whose first scan is the next clock
message's, with every topic published again; in real time ~reset refuses. On the demo
conveyor, a message on ~inputs/part_present takes the simulated part sensor (X3, which also
feeds the counters' exact edges) until ~simulate hands it back."""
import os
import sys
import threading
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState, Temperature
from std_msgs.msg import Bool
from std_srvs.srv import Trigger

from plc_cell.msg import (AxisStatus, Counter, CounterArray, ForcedPoints, IoState, IoWords, RegisterBlock, ScanProgress,
                          Signal)
from plc_cell.srv import ForceDiscrete, ReadMemory, SimulateInputs, WriteMemory

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import wait_until  # noqa: E402

TIMEOUT = 20.0
NODE = "/vt/plc_node"
PERIOD_NS = 2000000  # scan_period 0.002
LAG_NS = 100000000   # the default ~virtual_time_lag, 0.1 s


def msg_type(topic):
    rel = topic[len(NODE) + 1:] if topic.startswith(NODE + "/") else topic
    if rel == "io":
        return IoState
    if rel == "io_words":
        return IoWords
    if rel == "forced":
        return ForcedPoints
    if rel.startswith("signals_stamped/"):
        return Signal
    if rel.startswith("signals/"):
        return None  # std_msgs/Bool: no stamp
    if rel.startswith("registers/"):
        return RegisterBlock
    if rel == "counters":
        return CounterArray
    if rel.startswith("counters/"):
        return Counter
    if rel.endswith("/status"):
        return AxisStatus
    if rel.startswith("temperature/"):
        return Temperature
    if topic.endswith("/joint_states"):
        return JointState
    raise AssertionError("a topic this test does not know: %s" % topic)


def wait_connected(pub_or_sub):
    """Until it has a connection, at most TIMEOUT: rospy has no event for "a connection is up"."""
    deadline = time.monotonic() + TIMEOUT
    while pub_or_sub.get_num_connections() == 0 and time.monotonic() < deadline:
        time.sleep(0.01)


class Driver(object):
    """Counts the messages of every topic stamped at or after t0, and keeps the latest."""

    def __init__(self):
        self.cond = threading.Condition()
        self.progress = None
        self.t0 = 0
        self.received = {}
        self.latest = {}
        self.subs = {}
        self.progress_sub = rospy.Subscriber(NODE + "/virtual_time/scanned", ScanProgress, self._progress,
                                             queue_size=1000)
        self.clock = rospy.Publisher("/vt/clock", Clock, queue_size=1000)
        self.start = rospy.Publisher(NODE + "/inputs_stamped/start", Signal, queue_size=100)
        rospy.wait_for_service(NODE + "/reset", TIMEOUT)
        self.reset_srv = rospy.ServiceProxy(NODE + "/reset", Trigger)
        # The progress after a ~reset is one message: it is lost if this subscriber is not
        # connected yet when the first reset is called.
        wait_connected(self.progress_sub)

    def _progress(self, m):
        with self.cond:
            self.progress = m
            self.cond.notify_all()

    def _msg(self, m, topic):
        with self.cond:
            if m.header.stamp.to_nsec() < self.t0:
                return
            self.received[topic] = self.received.get(topic, 0) + 1
            self.latest[topic] = m
            self.cond.notify_all()

    def subscribe_all(self, topics):
        for t in topics:
            mt = msg_type(t)
            if mt is not None and t not in self.subs:
                self.subs[t] = rospy.Subscriber(t, mt, self._msg, t, queue_size=10000)
        for pub_or_sub in list(self.subs.values()) + [self.progress_sub, self.clock, self.start]:
            wait_connected(pub_or_sub)

    def wait(self, pred):
        return wait_until(self.cond, pred, TIMEOUT)

    def reset(self, t0):
        with self.cond:
            self.t0 = t0
            self.received = {}
            self.latest = {}
            self.progress = None
        r = self.reset_srv()
        assert r.success, r.message
        return r

    def complete(self, stamp):
        p = self.progress
        if p is None or p.header.stamp.to_nsec() < stamp:
            return False
        return all(self.received.get(t, 0) >= n for t, n in zip(p.topics, p.published) if t in self.subs)

    def scan(self, stamp):
        """Clock for the scan at stamp; True once its every message is in."""
        self.clock.publish(Clock(clock=rospy.Time(nsecs=stamp + LAG_NS)))
        return self.wait(lambda: self.complete(stamp))


class VirtualTimeSyncTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("virtual_time_sync_test", anonymous=True)
        cls.d = Driver()
        d = cls.d
        d.reset(0)
        assert d.wait(lambda: d.progress is not None), "no ~virtual_time/scanned after ~reset"
        d.subscribe_all(d.progress.topics)
        cls.t0 = 1000 * 10 ** 9

    def fresh(self):
        """A fresh cell whose scans are stamped from a new t0 on."""
        VirtualTimeSyncTest.t0 += 100 * 10 ** 9
        self.d.reset(self.t0)
        return self.t0

    def test_counts_cover_every_message_of_a_scan(self):
        d = self.d
        t0 = self.fresh()
        self.assertTrue(d.wait(lambda: d.progress is not None and d.progress.scans == 0))
        p = d.progress
        self.assertEqual(p.scan_period.to_nsec(), PERIOD_NS)
        self.assertEqual(p.lag.to_nsec(), LAG_NS)
        self.assertEqual(p.fault, "")
        self.assertEqual(len(p.topics), len(p.published))
        self.assertTrue(all(n == 0 for n in p.published), "counts start from 0 at ~reset")
        for name in ("io", "forced", "signals_stamped/motor", "registers/sums", "counters", "counters/belt",
                     "motion/slide/status", "temperature/oven_temp"):
            self.assertIn(NODE + "/" + name, p.topics)
        self.assertIn("/vt/joint_states", p.topics)
        for k in range(60):
            if k == 10 or k == 40:  # the start input, on at scan 10 and off at 40
                before = d.progress.inputs
                d.start.publish(Signal(header=rospy.Header(stamp=rospy.Time(nsecs=t0 + k * PERIOD_NS)),
                                       data=(k == 10)))
                self.assertTrue(d.wait(lambda: d.progress.inputs == before + 1), "the input is not acknowledged")
            stamp = t0 + k * PERIOD_NS
            self.assertTrue(d.scan(stamp), "scan %d: not every message arrived" % k)
            with d.cond:
                p = d.progress
                self.assertEqual(p.header.stamp.to_nsec(), stamp)
                self.assertEqual(p.scans, k + 1)
                for t, n in zip(p.topics, p.published):
                    if t in d.subs:
                        self.assertEqual(d.received.get(t, 0), n, "%s at scan %d" % (t, k))
                        if n:  # the latest is this scan's, or an earlier one's for a topic on change
                            self.assertLessEqual(d.latest[t].header.stamp.to_nsec(), stamp, t)
                counts = dict(zip(p.topics, p.published))
            # Every scan publishes the rate topics (~publish_every_scan); ~io when it changes.
            self.assertEqual(counts[NODE + "/registers/sums"], k + 1)
            self.assertEqual(counts[NODE + "/temperature/oven_temp"], k + 1)
            self.assertEqual(counts[NODE + "/counters/belt"], k + 1)
            with d.cond:
                for t in (NODE + "/registers/sums", NODE + "/temperature/oven_temp", NODE + "/motion/slide/status"):
                    self.assertEqual(d.latest[t].header.stamp.to_nsec(), stamp, t)
        with d.cond:
            self.assertFalse(d.latest[NODE + "/io"].y[0], "the motor follows the start input")
            self.assertEqual(counts[NODE + "/signals_stamped/motor"], 3, "first scan, on at 10, off at 40")

    def test_reset_gives_a_fresh_cell(self):
        d = self.d
        t0 = self.fresh()
        write = rospy.ServiceProxy(NODE + "/write", WriteMemory)
        read = rospy.ServiceProxy(NODE + "/read", ReadMemory)
        force = rospy.ServiceProxy(NODE + "/force", ForceDiscrete)
        for k in range(3):
            self.assertTrue(d.scan(t0 + k * PERIOD_NS))
        self.assertTrue(write("R11", [5]).success)
        self.assertTrue(force("Y1", True).success)
        self.assertTrue(d.scan(t0 + 3 * PERIOD_NS))
        self.assertEqual(d.latest[NODE + "/registers/sums"].values[0], 5)
        resets = d.progress.resets
        t1 = self.fresh()
        self.assertTrue(d.wait(lambda: d.progress is not None and d.progress.resets == resets + 1),
                        "no ~virtual_time/scanned after ~reset")
        self.assertEqual(d.progress.scans, 0)
        self.assertEqual(list(read("R11", 1).values), [0], "memory is fresh")
        self.assertTrue(d.scan(t1))  # the fresh cell's first scan is this clock's
        with d.cond:
            self.assertEqual(d.progress.scans, 1)
            self.assertEqual(d.progress.header.stamp.to_nsec(), t1)
            for t in d.subs:  # every topic published again, as on start, stamped with that scan
                self.assertIn(t, d.latest, "%s not published at the fresh cell's first scan" % t)
                self.assertEqual(d.latest[t].header.stamp.to_nsec(), t1, t)
            self.assertEqual(list(d.latest[NODE + "/forced"].addresses), [], "nothing forced any more")
            self.assertEqual(d.latest[NODE + "/registers/sums"].values[0], 0)

    def test_part_sensor_is_the_topics_until_simulate(self):
        # The demo's simulation: a part at X3 from 1 s to 3.5 s, every 5 s.
        d = DemoPartSensor()
        ms, s = 1000000, 1000000000
        d.clock.publish(Clock(clock=rospy.Time(0)))  # the cell's time 0: its first clock message
        self.assertTrue(d.scan_to(2 * s))
        self.assertEqual(d.changes, [(0, False), (1 * s, True)])
        d.part.publish(Bool(False))
        t = 2 * s
        while d.changes[-1][1] and t < 3 * s:  # the next scans apply it (another connection)
            t += ms
            self.assertTrue(d.scan_to(t))
        t_off = d.changes[-1][0]
        self.assertFalse(d.changes[-1][1], "~inputs/part_present false never reached X3")
        self.assertLess(t_off, 3 * s)
        self.assertTrue(d.scan_to(12 * s))
        self.assertEqual(d.changes[-1], (t_off, False), "the simulation's parts at 6 s and 11 s still came")
        bad = d.simulate(["start_button"])  # X0: the demo simulates no start button
        self.assertFalse(bad.success)
        self.assertIn("no signal on X0", bad.message)
        self.assertFalse(d.simulate(["conveyor_run"]).success)
        r = d.simulate(["part_present"])
        self.assertTrue(r.success, r.message)
        self.assertEqual(list(r.simulated), ["X3"])
        # At 12 s a part is at the sensor (11 s to 13.5 s): ON at the next scan, OFF at 13.5 s.
        self.assertTrue(d.scan_to(14 * s))
        self.assertEqual(d.changes[-2:], [(12 * s + ms, True), (13500 * ms, False)])

    def test_reset_refuses_in_real_time(self):
        rospy.wait_for_service("/rt/plc_node/reset", TIMEOUT)
        r = rospy.ServiceProxy("/rt/plc_node/reset", Trigger)()
        self.assertFalse(r.success)
        self.assertIn("virtual time only", r.message)


class DemoPartSensor(object):
    """/demo/plc_node: the clock, the part sensor's changes and ~virtual_time/scanned."""
    NODE = "/demo/plc_node"
    SIGNAL = NODE + "/signals_stamped/part_present"
    LAG_NS = 100000000  # the default ~virtual_time_lag

    def __init__(self):
        self.cond = threading.Condition()
        self.changes = []  # (stamp ns, level) of signals_stamped/part_present
        self.progress = None
        self.clock = rospy.Publisher("/demo/clock", Clock, queue_size=1000)
        self.part = rospy.Publisher(self.NODE + "/inputs/part_present", Bool, queue_size=10)
        self.subs = [rospy.Subscriber(self.SIGNAL, Signal, self._signal, queue_size=1000),
                     rospy.Subscriber(self.NODE + "/virtual_time/scanned", ScanProgress, self._progress,
                                      queue_size=1000)]
        for c in self.subs + [self.clock, self.part]:
            deadline = time.monotonic() + TIMEOUT
            while c.get_num_connections() == 0 and time.monotonic() < deadline:
                time.sleep(0.01)  # rospy has no event for "a connection is up"
        rospy.wait_for_service(self.NODE + "/simulate", TIMEOUT)
        self.simulate = rospy.ServiceProxy(self.NODE + "/simulate", SimulateInputs)

    def _signal(self, m):
        with self.cond:
            self.changes.append((m.header.stamp.to_nsec(), m.data))
            self.cond.notify_all()

    def _progress(self, m):
        with self.cond:
            self.progress = m
            self.cond.notify_all()

    def _complete(self, stamp):
        p = self.progress
        if p is None or p.header.stamp.to_nsec() < stamp:
            return False
        return len(self.changes) >= dict(zip(p.topics, p.published))[self.SIGNAL]

    def scan_to(self, stamp):
        """Every scan up to stamp (ns), with every change of the sensor it published."""
        self.clock.publish(Clock(clock=rospy.Time(nsecs=stamp + self.LAG_NS)))
        return wait_until(self.cond, lambda: self._complete(stamp), TIMEOUT)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "virtual_time_sync_test", VirtualTimeSyncTest)
