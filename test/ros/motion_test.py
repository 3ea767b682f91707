#!/usr/bin/env python3
"""rostest: a motion table loaded by service, run with the action; JointState reaches
the target; bad tables are refused with code and line; cancel decelerates."""
import threading
import time
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalID, GoalStatus, GoalStatusArray
from sensor_msgs.msg import JointState

from plc_cell.msg import (AxisStatus, RunMotionTableActionFeedback, RunMotionTableActionGoal,
                          RunMotionTableActionResult)
from plc_cell.srv import LoadMotionTable, MotionCommand, SetMotionParams

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
        cls.joints = Latest("/plc_node/joint_states", JointState)
        cls.status = Latest(NS + "status", AxisStatus)
        # P8 = 200 ms: 460 kHz/0.2 s = 2.3 MHz/s.
        values = [1, 2000, 2000, 2, 460000, 141, 1000, 0, 200, 0x100, 0, 0, 0, 500, 0, 0xFFFFFFFF, 0, 1]
        res = cls.params(values)
        assert res.success, res.message

    def test_1_bad_table_and_bad_params_are_refused(self):
        res = self.load("SPD 5000\nDRV ADR,+,10,Ps\nGOTO NEXT\nSPD 0\nDRV ADR,+,1,Ps\nGOTO NEXT\nMEND\n")
        self.assertFalse(res.success)
        self.assertEqual(res.error_code, 31)
        self.assertEqual(res.line, 4)
        res = self.params([1, 2000, 2000, 2, 460000, 141, 1000, 0, 30001, 0x100, 0, 0, 0, 500, 0, 0xFFFFFFFF, 0, 1])
        self.assertFalse(res.success)
        self.assertEqual(res.error_code, 9)

    def test_2_loaded_table_runs_to_its_end_with_the_action(self):
        res = self.load("001 SPD 20000\n    DRV ADR,+,20000,Ut\n    GOTO NEXT\n002 SPD 10000\n"
                        "    DRV ADR,-,5000,Ps\n    GOTO NEXT\nMEND\n")
        self.assertTrue(res.success, res.message)
        self.assertEqual(res.steps, 2)
        start = self.joints.wait_for(lambda m: True)
        self.assertEqual(start.name, ["slide"])
        x0 = start.position[0]
        self.action.send_goal("")
        done = self.action.wait_for_result()
        self.assertIsNotNone(done)
        self.assertEqual(done.status.status, GoalStatus.SUCCEEDED, done.status.text)
        result = done.result
        feedback = self.action.feedback_of_goal()
        self.assertTrue(result.success)
        self.assertAlmostEqual(result.position, x0 + 15.0, places=6)
        self.assertTrue(any(f.step == 1 for f in feedback))
        self.assertTrue(any(f.step == 2 for f in feedback))
        js = self.joints.wait_for(lambda m: abs(m.position[0] - (x0 + 15.0)) < 1e-9 and m.velocity[0] == 0.0)
        self.assertIsNotNone(js)
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

    def test_4_unknown_command(self):
        res = self.command("jump", 0, 0)
        self.assertFalse(res.success)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "motion_test", MotionTest)
