#!/usr/bin/python3
"""rostest: a motion table loaded by service, run with the action; JointState reaches
the target; bad tables are refused with code and line; cancel decelerates."""
import logging
import threading
import time
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalID, GoalStatus, GoalStatusArray
from sensor_msgs.msg import JointState

from plc_cell.msg import (AxisStatus, RunMotionTableActionFeedback, RunMotionTableActionGoal,
                          RunMotionTableActionResult)
from plc_cell.srv import LoadMotionTable, MotionCommand, MotionCommandRequest, ReadMemory, SetMotionParams

NS = "/plc_node/motion/slide/"
TIMEOUT = 30.0


class Latest(object):
    """Keeps the messages of a topic and lets a test wait for a condition."""

    def __init__(self, topic, msg_type):
        self.msg = None
        self.all = []
        self.cond = threading.Condition()
        self.sub = rospy.Subscriber(topic, msg_type, self._cb)

    def _cb(self, msg):
        with self.cond:
            self.msg = msg
            self.all.append(msg)
            self.cond.notify_all()

    def wait_for(self, pred, timeout=TIMEOUT):
        deadline = time.monotonic() + timeout
        with self.cond:
            while self.msg is None or not pred(self.msg):
                left = deadline - time.monotonic()
                if left <= 0:
                    return None
                self.cond.wait(left)
            return self.msg


class ActionClient(object):
    """The action's topic protocol (goal, cancel, feedback, result): what
    actionlib's client does, without needing python3-actionlib."""

    def __init__(self, ns):
        self.goal_pub = rospy.Publisher(ns + "/goal", RunMotionTableActionGoal, queue_size=1)
        self.cancel_pub = rospy.Publisher(ns + "/cancel", GoalID, queue_size=1)
        self.results = Latest(ns + "/result", RunMotionTableActionResult)
        self.feedback = Latest(ns + "/feedback", RunMotionTableActionFeedback)
        self.status = Latest(ns + "/status", GoalStatusArray)
        self.count = 0
        self.id = None

    def wait_for_server(self, timeout):
        """Every connection of the protocol is up, checked at each of the server's
        status messages (actionlib publishes them at 5 Hz): no goal or result is lost."""
        def connected(_):
            return (self.goal_pub.get_num_connections() > 0 and self.cancel_pub.get_num_connections() > 0
                    and self.results.sub.get_num_connections() > 0
                    and self.feedback.sub.get_num_connections() > 0)
        return connected(self.status.wait_for(connected, timeout))

    def send_goal(self, table=""):
        self.count += 1
        self.id = "motion_test_%d" % self.count
        g = RunMotionTableActionGoal()
        g.header.stamp = rospy.Time.now()
        g.goal_id.id = self.id
        g.goal_id.stamp = g.header.stamp
        g.goal.table = table
        self.goal_pub.publish(g)

    def cancel(self):
        self.cancel_pub.publish(GoalID(id=self.id))

    def wait_for_result(self, timeout=TIMEOUT):
        gid = self.id
        return self.results.wait_for(lambda m: m.status.goal_id.id == gid, timeout)

    def feedback_of_goal(self):
        return [m.feedback for m in self.feedback.all if m.status.goal_id.id == self.id]


class MotionTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("motion_test", anonymous=True)
        rospy.wait_for_service(NS + "load_table", timeout=30)
        cls.load = rospy.ServiceProxy(NS + "load_table", LoadMotionTable)
        cls.params = rospy.ServiceProxy(NS + "set_params", SetMotionParams)
        cls.command = rospy.ServiceProxy(NS + "command", MotionCommand)
        cls.action = ActionClient(NS + "run")
        assert cls.action.wait_for_server(30)
        cls.joints = Latest("/joint_states", JointState)  # the node's namespace, not private
        cls.status = Latest(NS + "status", AxisStatus)
        # The ramps are the cell YAML's params: P8 = 200 ms, 460 kHz/0.2 s = 2.3 MHz/s.

    def test_1_bad_table_and_bad_params_are_refused(self):
        res = self.load("SPD 5000\nDRV ADR,+,10,Ps\nGOTO NEXT\nSPD 0\nDRV ADR,+,1,Ps\nGOTO NEXT\nMEND\n")
        self.assertFalse(res.success)
        self.assertEqual(res.error_code, 31)
        self.assertEqual(res.line, 4)
        res = self.params(values=[1, 2000, 2000, 2, 460000, 141, 1000, 0, 30001, 0x100, 0, 0, 0, 500, 0, 0xFFFFFFFF, 0, 1])
        self.assertFalse(res.success)
        self.assertEqual(res.error_code, 9)
        self.assertEqual(res.message, "P8: 30001 out of range 0..30000")
        # P17 has no code in the manual; the value is still refused, by name.
        res = self.params(values=[1, 2000, 2000, 2, 460000, 141, 1000, 0, 200, 0x100, 0, 0, 0, 500, 0, 0xFFFFFFFF, 0, 256])
        self.assertFalse(res.success)
        self.assertEqual(res.message, "P17: 256 out of range 0..255")
        # Named, a partial update: each value against its range, nothing changed on a refusal.
        res = self.params(names=["p8"], values=[30001])
        self.assertFalse(res.success)
        self.assertEqual((res.error_code, res.message), (9, "P8: 30001 out of range 0..30000"))
        res = self.params(names=["p18"], values=[1])
        self.assertFalse(res.success)
        self.assertEqual(res.message, "'p18': no such parameter (p0 ... p17)")
        res = self.params(names=["p8", "P8"], values=[100, 100])
        self.assertFalse(res.success)
        self.assertEqual(res.message, "P8 given twice")
        res = self.params(names=["p8", "p12"], values=[100])
        self.assertFalse(res.success)
        self.assertEqual(res.message, "2 names but 1 values: one value per name")
        res = self.params(values=[200])
        self.assertFalse(res.success)
        self.assertIn("give the 18 values P0..P17 in order, or names with their values", res.message)

    def test_2_loaded_table_runs_to_its_end_with_the_action(self):
        res = self.load("001 SPD 20000\n    DRV ADR,+,20000,Ut\n    GOTO NEXT\n002 SPD 10000\n"
                        "    DRV ADR,-,5000,Ps\n    GOTO NEXT\nMEND\n")
        self.assertTrue(res.success, res.message)
        self.assertEqual(res.steps, 2)
        start = self.joints.wait_for(lambda m: True)
        self.assertEqual(start.name, ["slide"])
        x0 = start.position[0]
        p0 = self.status.wait_for(lambda m: True).position
        self.action.send_goal("")
        done = self.action.wait_for_result()
        self.assertIsNotNone(done)
        self.assertEqual(done.status.status, GoalStatus.SUCCEEDED, done.status.text)
        result = done.result
        feedback = self.action.feedback_of_goal()
        self.assertTrue(result.success)
        self.assertAlmostEqual(result.position, p0 + 15.0, places=6)  # user units: mm
        self.assertTrue(any(f.step == 1 for f in feedback))
        self.assertTrue(any(f.step == 2 for f in feedback))
        # joint_states in m: 15000 pulses of 1 um.
        js = self.joints.wait_for(lambda m: abs(m.position[0] - (x0 + 0.015)) < 1e-12 and m.velocity[0] == 0.0)
        self.assertIsNotNone(js)
        st = self.status.wait_for(lambda m: not m.running)
        self.assertAlmostEqual(js.position[0], st.pulses * 1e-6, places=12)
        st = self.status.wait_for(lambda m: not m.running)
        self.assertTrue(st.finished)
        self.assertEqual(st.error, 0)

    def test_3_cancel_mid_move_decelerates(self):
        self.assertTrue(self.load("SPD 100000\nDRV ADR,+,10000000,Ps\nGOTO NEXT\nMEND\n").success)
        self.action.send_goal("")
        cruising = self.status.wait_for(lambda m: m.frequency == 100000.0)
        self.assertIsNotNone(cruising)
        n = len(self.status.all)
        self.action.cancel()
        done = self.action.wait_for_result()
        self.assertIsNotNone(done)
        self.assertEqual(done.status.status, GoalStatus.PREEMPTED)
        stopped = self.status.wait_for(lambda m: m.frequency == 0.0)
        self.assertIsNotNone(stopped)
        # A decelerated stop (100 kHz -> 141 Hz at 2.3 MHz/s: 43 ms) shows speeds in between.
        between = [m.frequency for m in self.status.all[n:] if 0.0 < m.frequency < 100000.0]
        self.assertTrue(between, "no intermediate speed seen after the cancel")
        # and the table is no longer running
        self.assertFalse(self.status.wait_for(lambda m: m.running, timeout=0.5))

    def test_5_cancel_reports_after_the_stop_and_the_next_goal_runs(self):
        """actionlib's client: cancel -> decelerated stop with feedback all along, the
        PREEMPTED result carries the final position, the next goal is accepted at once,
        and the client logs no warning or error."""
        import actionlib
        from plc_cell.msg import RunMotionTableAction, RunMotionTableGoal

        class Capture(logging.Handler):
            """Client warnings and errors. One is the client library's own: Python's
            SimpleActionClient.send_goal assigns its goal handle only after the goal is
            published, so a server that accepts at once can report ACTIVE before that
            and the client logs "not tracking" (ros/actionlib#206, any server; the log
            names no goal, and its call can come after send_goal has returned). That one
            is tolerated here; what it would hide, a transition of a goal after its
            result, is checked on the wire instead (the action's status topic)."""

            def __init__(self):
                logging.Handler.__init__(self, logging.WARNING)
                self.records = []

            def emit(self, record):
                if record.getMessage() != "Got a transition callback on a goal handle that we're not tracking":
                    self.records.append(record.getMessage())
        cap = Capture()
        seen = {}  # goal id -> the statuses the server reported for it, in order, without repeats
        lock = threading.Condition()

        def on_status(m):
            with lock:
                for st in m.status_list:
                    h = seen.setdefault(st.goal_id.id, [])
                    if not h or h[-1] != st.status:
                        h.append(st.status)
                lock.notify_all()
        status_sub = rospy.Subscriber(NS + "run/status", GoalStatusArray, on_status, queue_size=1000)
        logging.getLogger("rosout").addHandler(cap)
        goal_ids = []
        try:
            self._cancel_sequence(actionlib, RunMotionTableAction, RunMotionTableGoal, goal_ids)
        finally:
            logging.getLogger("rosout").removeHandler(cap)
        self.assertEqual(cap.records, [])
        # The server's word for each goal ends in its terminal state and never leaves it:
        # the cancelled goal PREEMPTED (nothing after the result), the next one SUCCEEDED.
        # The two results have been received, so their last status arrays are waited for.
        deadline = time.monotonic() + TIMEOUT
        want = {goal_ids[0]: GoalStatus.PREEMPTED, goal_ids[1]: GoalStatus.SUCCEEDED}
        with lock:
            while not all(seen.get(g, [None])[-1] == s for g, s in want.items()):
                left = deadline - time.monotonic()
                if left <= 0:
                    break
                lock.wait(left)
        status_sub.unregister()
        with lock:
            for g, s in want.items():
                h = seen.get(g, [])
                self.assertIn(s, h, "goal %s: statuses %s" % (g, h))
                self.assertEqual(h[h.index(s):], [s], "goal %s changed after its result: %s" % (g, h))

    def _cancel_sequence(self, actionlib, RunMotionTableAction, RunMotionTableGoal, goal_ids):
        read = rospy.ServiceProxy("/plc_node/read", ReadMemory)
        # P12 = 2 s: 460 kHz / 2 s = 230 kHz/s, so 100 kHz -> 141 Hz takes 0.43 s of
        # deceleration, about 20 feedback messages at 50 Hz.
        # Only P12 changes: the YAML's P8 (200 ms) stays the acceleration.
        self.assertTrue(self.params(names=["p12"], values=[2000]).success)
        client = actionlib.SimpleActionClient(NS + "run", RunMotionTableAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(TIMEOUT)))

        def send(goal, feedback_cb=None):
            client.send_goal(goal, feedback_cb=feedback_cb)
            goal_ids.append(client.gh.comm_state_machine.action_goal.goal_id.id)
        fb = []
        cond = threading.Condition()

        def on_feedback(f):
            with cond:
                fb.append(f)
                cond.notify_all()

        def wait_feedback(pred):
            deadline = time.monotonic() + TIMEOUT
            with cond:
                while not any(pred(f) for f in fb):
                    left = deadline - time.monotonic()
                    if left <= 0:
                        return False
                    cond.wait(left)
                return True

        self.assertTrue(self.load("SPD 100000\nDRV ADR,+,10000000,Ps\nGOTO NEXT\nMEND\n").success)
        send(RunMotionTableGoal(table=""), feedback_cb=on_feedback)
        self.assertTrue(wait_feedback(lambda f: abs(f.velocity - 100.0) < 1e-9), "never cruised at 100 kHz")
        with cond:
            n = len(fb)
        client.cancel_goal()
        self.assertTrue(client.wait_for_result(rospy.Duration(TIMEOUT)))
        self.assertEqual(client.get_state(), GoalStatus.PREEMPTED)
        result = client.get_result()
        with cond:
            after = [f.velocity for f in fb[n:]]
        # Feedback went on during the deceleration, with speeds between cruise and standstill.
        self.assertTrue([v for v in after if 0.0 < v < 100.0], "no feedback during the deceleration: %s" % after)
        # The result came once the axis stood still: DR4088 read now, and the next
        # status, show the same pulse count, and the axis is not moving.
        dr = read("DR4088", 1)
        self.assertTrue(dr.success, dr.message)
        pos = dr.values[0] - (1 << 32) if dr.values[0] >= (1 << 31) else dr.values[0]
        self.assertEqual(result.pulses, pos)
        self.assertAlmostEqual(result.position, pos * 0.001, places=9)
        k = len(self.status.all)
        st = self.status.wait_for(lambda m: len(self.status.all) > k + 1)
        self.assertIsNotNone(st)
        self.assertEqual(st.pulses, result.pulses)
        self.assertEqual(st.frequency, 0.0)
        self.assertFalse(st.running)
        # The next goal straight after the result: accepted and run to its end.
        send(RunMotionTableGoal(table="SPD 10000\nDRV ADR,+,1000,Ps\nGOTO NEXT\nMEND\n"))
        self.assertTrue(client.wait_for_result(rospy.Duration(TIMEOUT)))
        self.assertEqual(client.get_state(), GoalStatus.SUCCEEDED, client.get_goal_status_text())
        self.assertEqual(client.get_result().pulses, result.pulses + 1000)
        self.assertTrue(self.params(names=["P12"], values=[0]).success)

    def test_4_unknown_command(self):
        res = self.command(42, 0, 0)
        self.assertFalse(res.success)
        self.assertIn("unknown", res.message)
        res = self.command(0, 0, 0)  # an empty request
        self.assertFalse(res.success)

    def test_6_command_constants(self):
        self.assertEqual((MotionCommandRequest.START, MotionCommandRequest.PAUSE, MotionCommandRequest.RESUME,
                          MotionCommandRequest.ABORT, MotionCommandRequest.HOME), (1, 2, 3, 4, 5))
        # An axis at rest: ABORT and PAUSE are accepted or refused with a reason, never "unknown".
        for c in (MotionCommandRequest.ABORT, MotionCommandRequest.PAUSE):
            res = self.command(c, 0, 0)
            self.assertNotIn("unknown", res.message)
        x0 = self.status.wait_for(lambda m: not m.running).pulses
        self.assertTrue(self.load("SPD 10000\nDRV ADR,+,500,Ps\nGOTO NEXT\nMEND\n").success)
        res = self.command(MotionCommandRequest.START, 0, 0)
        self.assertTrue(res.success, res.message)
        st = self.status.wait_for(lambda m: m.pulses == x0 + 500 and not m.running and m.frequency == 0.0)
        self.assertIsNotNone(st)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "motion_test", MotionTest)
