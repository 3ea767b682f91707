#!/usr/bin/python3
"""rostest for plc_node: topics in, program outputs observed on topics out, services."""
import json
import os
import subprocess
import sys
import threading
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from std_msgs.msg import Bool
from std_srvs.srv import SetBool

from plc_cell.msg import ForcedPoints, IoState, IoWords, RegisterBlock
from plc_cell.srv import ForceDiscrete, LoadProgram, ReadMemory, ReleaseDiscrete, WriteMemory

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from latest_message import Latest  # noqa: E402
from tool_path import find_tool  # noqa: E402

NS = "/plc_node/"
TIMEOUT = 10.0




class PlcNodeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("plc_node_test", anonymous=True)
        for s in ["read", "write", "force", "release", "set_run_mode", "load_program"]:
            rospy.wait_for_service(NS + s, timeout=30)
        cls.read = rospy.ServiceProxy(NS + "read", ReadMemory)
        cls.write = rospy.ServiceProxy(NS + "write", WriteMemory)
        cls.force = rospy.ServiceProxy(NS + "force", ForceDiscrete)
        cls.release = rospy.ServiceProxy(NS + "release", ReleaseDiscrete)
        cls.forced = Latest(NS + "forced", ForcedPoints, timeout=TIMEOUT)
        cls.diag = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)
        cls.run_mode = rospy.ServiceProxy(NS + "set_run_mode", SetBool)
        cls.load = rospy.ServiceProxy(NS + "load_program", LoadProgram)
        cls.start_pub = rospy.Publisher(NS + "inputs/start", Bool, queue_size=1, latch=True)
        cls.io = Latest(NS + "io", IoState, timeout=TIMEOUT)
        cls.io_words = Latest(NS + "io_words", IoWords, timeout=TIMEOUT)
        cls.motor = Latest(NS + "signals/motor", Bool, timeout=TIMEOUT)
        cls.part_seen = Latest(NS + "signals/part_seen", Bool, timeout=TIMEOUT)
        cls.sums = Latest(NS + "registers/sums", RegisterBlock, timeout=TIMEOUT)  # R10, R11, R12, R20

    def setUp(self):
        self.assertTrue(self.run_mode(True).success)
        self.assertTrue(self.release("").success)

    def test_topic_in_drives_output_topic_out(self):
        self.start_pub.publish(Bool(True))
        m = self.motor.wait_for(lambda m: m.data)
        self.assertTrue(m.data, "Y0 (motor) did not follow X0 (start) on signals/motor")
        io = self.io.wait_for(lambda m: m.y[0])
        self.assertTrue(io.x[0] and io.y[0])
        self.start_pub.publish(Bool(False))
        self.assertFalse(self.motor.wait_for(lambda m: not m.data).data)

    def test_io_message_shape(self):
        io = self.io.wait_for(lambda m: True)
        self.assertEqual(len(io.x), 256)
        self.assertEqual(len(io.y), 256)
        self.assertEqual(io.header.frame_id, "")  # no ~frame_id: the cell name is no frame
        self.assertGreater(io.header.stamp.to_sec(), 0)
        self.assertTrue(io.run)

    def test_io_words_are_the_image_as_16_bit_words(self):
        """~io_words: x[i] = WX(16 i), bit b = X(16 i + b); the same image as ~io."""
        self.assertTrue(self.write("X3", [1]).success)  # part_present: the program sets Y1
        self.start_pub.publish(Bool(True))               # X0: the program sets Y0
        w = self.io_words.wait_for(lambda m: m.x[0] & 0x9 == 0x9 and m.y[0] & 0x3 == 0x3)
        self.assertIsNotNone(w)
        self.assertEqual((len(w.x), len(w.y)), (16, 16))
        self.assertEqual(w.x[0] & 0x9, 0x9, "X0 and X3 are bits 0 and 3 of x[0]")
        self.assertEqual(w.y[0] & 0x3, 0x3, "Y0 and Y1 are bits 0 and 1 of y[0]")
        self.assertEqual(list(w.x[1:]), [0] * 15)
        self.assertTrue(w.run)
        # Every point as ~io shows it in the message of the same stamp (both are published
        # together: the latest of each match once neither is mid-delivery).
        pair = []

        def same_stamp(io):
            words = self.io_words.msg
            pair[:] = [io, words]
            return words.header.stamp == io.header.stamp

        self.io.wait_for(same_stamp)
        io, w = pair
        self.assertEqual(io.header.stamp, w.header.stamp)
        for i in range(256):
            self.assertEqual(bool(w.x[i // 16] >> (i % 16) & 1), io.x[i], "X%d" % i)
            self.assertEqual(bool(w.y[i // 16] >> (i % 16) & 1), io.y[i], "Y%d" % i)
        self.start_pub.publish(Bool(False))
        self.write("X3", [0])

    def test_write_then_program_computes(self):
        r = self.write("R11", [5, 7])
        self.assertTrue(r.success, r.message)
        m = self.sums.wait_for(lambda m: list(m.values[:3]) == [12, 5, 7])
        self.assertEqual(list(m.values[:3]), [12, 5, 7], "R10 != R11 + R12 on registers/sums")
        self.assertEqual((m.name, m.address, m.header.frame_id), ("sums", "R10:3,R20", ""))
        self.assertEqual(list(self.read("R11", 2).values), [5, 7])

    def test_named_signals_and_double_words(self):
        self.assertTrue(self.write("DR100", [0x12345678]).success)
        self.assertEqual(list(self.read("R100", 2).values), [0x5678, 0x1234])
        self.write("part_present", [1])
        self.assertTrue(self.part_seen.wait_for(lambda m: m.data).data)
        self.write("M10", [1])
        self.assertFalse(self.part_seen.wait_for(lambda m: not m.data).data)
        self.write("M10", [0])
        self.write("part_present", [0])

    def test_bad_requests_are_refused_and_change_nothing(self):
        r = self.read("Q5", 1)
        self.assertFalse(r.success)
        self.assertIn("Q5", r.message)
        self.assertIn("unknown prefix", r.message)
        self.assertTrue(self.write("R8070", [1, 1]).success)
        before = list(self.read("R8070", 2).values)
        r = self.write("R8070", [9, 9, 9])  # runs past R8071
        self.assertFalse(r.success)
        self.assertIn("out of range", r.message)
        self.assertEqual(list(self.read("R8070", 2).values), before)
        r = self.write("R5", [70000])
        self.assertFalse(r.success)
        r = self.force("R5", True)
        self.assertFalse(r.success)
        self.assertIn("single discrete", r.message)
        r = self.release("R5")
        self.assertFalse(r.success)
        r = self.force("Y999", True)
        self.assertFalse(r.success)
        self.assertIn("Y999", r.message)
        # A 16-bit register takes -32768..65535; the message names the range and the value.
        r = self.write("R5", [-40000])
        self.assertFalse(r.success)
        self.assertIn("-32768..65535", r.message)
        self.assertIn("-40000", r.message)

    def test_negative_values_are_written_as_twos_complement(self):
        # The docs say register values are signed: -500 is stored as 65036 (0xFE0C).
        self.assertTrue(self.write("R30", [-500, 65535, -32768]).success)
        self.assertEqual(list(self.read("R30", 3).values), [65036, 65535, 32768])
        self.assertTrue(self.write("DR40", [-2]).success)
        self.assertEqual(list(self.read("DR40", 1).values), [0xFFFFFFFE])
        r = self.write("DR40", [-2147483649])
        self.assertFalse(r.success)
        self.assertIn("-2147483648..4294967295", r.message)
        r = self.write("M3", [-1])
        self.assertFalse(r.success)
        self.assertIn("0..1", r.message)

    def test_force_disable_holds_the_output(self):
        self.start_pub.publish(Bool(False))
        self.assertFalse(self.motor.wait_for(lambda m: not m.data).data)
        r = self.force("Y0", True)
        self.assertTrue(r.success, r.message)
        self.assertTrue(self.motor.wait_for(lambda m: m.data).data)
        # The program writes Y0 = X0 = 0 every scan, but a disabled point keeps its state.
        self.assertEqual(list(self.read("Y0", 1).values), [1])
        # Two more ~io images (each taken after a scan) still show Y0 on, X0 off.
        seq = self.io.wait_for(lambda m: True).header.seq
        io = self.io.wait_for(lambda m: m.header.seq >= seq + 2)
        self.assertGreaterEqual(io.header.seq, seq + 2)
        self.assertTrue(io.y[0] and not io.x[0])
        self.assertEqual(list(self.read("Y0", 1).values), [1])
        r = self.release("Y0")
        self.assertTrue(r.success, r.message)
        self.assertEqual(list(r.released), ["Y0"])
        self.assertFalse(self.motor.wait_for(lambda m: not m.data).data)

    def test_forced_points_show_on_a_latched_topic_and_diagnostics(self):
        # A user who locks X3 by mistake must see it: ~forced lists it, /diagnostics warns.
        self.assertTrue(self.force("X3", False).success)
        m = self.forced.wait_for(lambda m: "X3" in m.addresses)
        self.assertEqual(list(m.addresses), ["X3"])
        self.assertEqual(list(m.states), [False])
        late = Latest(NS + "forced", ForcedPoints, timeout=TIMEOUT)  # latched: a late subscriber sees it
        self.assertEqual(list(late.wait_for(lambda m: True).addresses), ["X3"])

        def forced_status(a):
            for st in a.status:
                if st.name.endswith("forced points"):
                    return st
            return None
        d = self.diag.wait_for(lambda a: forced_status(a) is not None and "X3" in forced_status(a).message)
        st = forced_status(d)
        self.assertEqual(st.level, 1, st.message)  # WARN
        self.assertIn("X3=OFF", st.message)
        # The input no longer follows its topic while forced.
        self.write("part_present", [1])
        self.assertEqual(list(self.read("X3", 1).values), [0])
        r = self.release("")
        self.assertEqual(list(r.released), ["X3"])
        self.assertEqual(list(self.forced.wait_for(lambda m: not m.addresses).addresses), [])
        d = self.diag.wait_for(lambda a: forced_status(a) is not None and forced_status(a).level == 0)
        self.assertEqual(forced_status(d).message, "no point forced")
        self.write("part_present", [0])

    def test_run_stop(self):
        self.start_pub.publish(Bool(True))
        self.assertTrue(self.motor.wait_for(lambda m: m.data).data)
        self.assertTrue(self.run_mode(False).success)
        io = self.io.wait_for(lambda m: not m.run)
        self.assertFalse(io.run)
        self.assertFalse(io.y[0], "outputs go off in STOP")
        self.assertTrue(self.run_mode(True).success)
        self.assertTrue(self.io.wait_for(lambda m: m.run and m.y[0]).y[0])
        self.start_pub.publish(Bool(False))

    def test_load_program_error_keeps_old_program(self):
        program = rospy.get_param(NS + "program")
        original = open(program).read()
        r = self.load(text="ORG X0\nOUT Q9\nEND\n")
        self.assertFalse(r.success)
        self.assertEqual(r.result, "refused")
        self.assertIn("test_cell.il:2:5", r.message)
        self.start_pub.publish(Bool(True))
        self.assertTrue(self.motor.wait_for(lambda m: m.data).data, "the old program stopped running")
        self.start_pub.publish(Bool(False))
        text = "ORG X0\nOUT Y0\nORG M1925\nFUN 8 S=321 D=R20\nEND\n"
        r = self.load(text=text)
        self.assertTrue(r.success, r.message)
        self.assertEqual(r.result, "applied")
        self.assertEqual(r.instructions, 5)
        self.assertEqual(self.sums.wait_for(lambda m: m.values[3] == 321).values[3], 321)
        # Through the change service: the program file rewritten, the change in its log.
        report = json.loads(r.report)
        self.assertEqual(open(program).read(), text)
        log = [json.loads(l) for l in open(program + ".changes.jsonl")]
        self.assertEqual([(e["result"], e["source"]) for e in log], [("refused", "service"), ("applied", "service")])
        self.assertEqual(log[-1]["new_hash"], report["new_hash"])
        r = self.load()  # reload the file named in the cell: the program just written, nothing changes
        self.assertTrue(r.success, r.message)
        self.assertIn("already running", r.message)
        r = self.load(text=original)  # the other tests' program again
        self.assertEqual(r.result, "applied", r.message)
        self.assertEqual(open(program).read(), original)

    def test_diagnostics_report_the_scan(self):
        diag = Latest("/diagnostics", DiagnosticArray, timeout=TIMEOUT)
        # Not diagnostic_updater's "Node starting up" announcement, which has no values.
        def scan(m):
            return [s for s in m.status if s.name.endswith("scan") and s.values]
        msg = diag.wait_for(lambda m: bool(scan(m)), timeout=15)
        self.assertIsNotNone(msg)
        st = scan(msg)[0]
        # RUN; on a loaded machine the 1 ms scan may also be late (a WARN or ERROR saying so).
        self.assertTrue(st.message.startswith("RUN"), st.message)
        keys = dict((kv.key, kv.value) for kv in st.values)
        self.assertGreater(int(keys["scans"]), 0)
        self.assertIn("cycle max (us)", keys)
        # Neither the cell nor the node chooses an engine: the default, native.
        self.assertTrue(keys["engine"].startswith("native: "), keys["engine"])

    def test_a_cell_with_no_counters_has_no_counters_topic(self):
        # test_cell.yaml has no counters: none of its topics is ~counters.
        rospy.wait_for_service(NS + "read", timeout=30)
        topics = [t for t, _ in rospy.get_published_topics()]
        self.assertIn(NS + "io", topics)
        self.assertNotIn(NS + "counters", topics)

    def test_a_misspelled_private_parameter_is_named_in_a_warning(self):
        """_io_rte:=50 (for io_rate) is not silently ignored: the node warns, naming it, and
        says nothing of the parameters it knows."""
        cell = os.path.join(os.path.dirname(os.path.abspath(__file__)), "test_cell.yaml")
        node = subprocess.Popen([find_tool("plc_node"), "__name:=misspelled", "_cell:=" + cell,
                                 "_io_rte:=50", "_io_rate:=5", "_autostart:=false"],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        killer = threading.Timer(30, node.kill)  # bounds the wait for the start-up line
        killer.start()
        try:
            for line in node.stdout:  # ROS_INFO: the start-up line comes after the check
                if "plc_node: cell" in line:
                    break
        finally:
            killer.cancel()
            node.terminate()
            _, err = node.communicate(timeout=30)
        self.assertIn("~io_rte is not a parameter of plc_node", err)
        self.assertNotIn("~io_rate", err)
        self.assertNotIn("~cell", err)


if __name__ == "__main__":
    rostest.rosrun("plc_cell", "plc_node_test", PlcNodeTest)
