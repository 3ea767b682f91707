#!/usr/bin/python3
"""Every service of plc_node called with generated arguments.

The services of each node are found at run time (rosservice), and each request is
built from its message definition: strings from a pool of valid and malformed
addresses, names, tables and programs; integers at and beyond their type's bounds;
NaN and infinities; arrays from empty to 10,000 elements. After each call the node must
still answer, and after each node's batch its scan must still be running: the scan
count of its diagnostics grows and the status is not a fault. A refused
call must say why. Run mode changes are left out: STOP is what ~set_run_mode is for.
The seed is fixed, so a failure repeats; the failing request is in the message.
"""
import random
import sys
import unittest

import rospy
import rosservice
import rostest

from diagnostic_msgs.msg import DiagnosticArray

NODES = ["/io_cell", "/axis_cell", "/counter_cell"]
CALLS_PER_SERVICE = 60
SKIP = {"set_run_mode", "get_loggers", "set_logger_level"}

STRINGS = ["", "R0", "X0", "Y0", "M1", "DR4088", "WY8", "R3839", "R99999", "D-1", "Q7", "R", "X256",
           "start", "pause", "resume", "abort", "home", "nonsense", "oven", "\x00", "R0 R1", "é", "x" * 5000,
           "001 SPD 1000\n    DRV ADR,+,100,Ps\n    GOTO NEXT\nMEND\n", "001 SPD 0\nMEND", "MEND",
           "ORG M1925\nOUT Y0\nEND\n", "LD\nEND", "FUN 9999\nEND", "/nonexistent.il", "/dev/zero"]


def int_values(bits, signed):
    lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
    return [lo, hi, 0, 1, -1 if signed else 2, lo + 1, hi - 1, 65535, 65536, 4294967295]


def field_value(rng, ftype):
    base = ftype.split("[")[0]
    if ftype.endswith("]"):
        n = rng.choice([0, 1, 2, 18, 100, 10000])
        return [field_value(rng, base) for _ in range(n)]
    if base == "string":
        return rng.choice(STRINGS)
    if base == "bool":
        return rng.choice([True, False])
    if base in ("float32", "float64"):
        return rng.choice([0.0, -1.0, 1e308, -1e308, float("nan"), float("inf"), 200.0, -273.2])
    for bits in (8, 16, 32, 64):
        if base in ("int%d" % bits, "uint%d" % bits):
            signed = base.startswith("int")
            v = rng.choice(int_values(bits, signed))
            lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
            return max(lo, min(hi, v))
    raise ValueError("no generator for " + ftype)


def make_request(rng, srv_class):
    req = srv_class._request_class()
    for name, ftype in zip(req.__slots__, req._slot_types):
        setattr(req, name, field_value(rng, ftype))
    return req


class ServiceFuzz(unittest.TestCase):
    def scans(self, node):
        """The node's scan count and level from its "<node>: scan" diagnostics status."""
        name = node.strip("/") + ": scan"
        for _ in range(50):
            msg = rospy.wait_for_message("/diagnostics", DiagnosticArray, timeout=10)
            for st in msg.status:
                if st.name == name:
                    values = {kv.key: kv.value for kv in st.values}
                    return int(values["scans"]), st.level, st.message
        self.fail("no %r status on /diagnostics" % name)

    def test_generated_calls(self):
        rng = random.Random(20261124)
        for node in NODES:
            rospy.wait_for_service(node + "/read", timeout=30)
            before, _, _ = self.scans(node)
            services = sorted(s for s in rosservice.get_service_list(namespace=node)
                              if s.rsplit("/", 1)[-1] not in SKIP)
            self.assertGreater(len(services), 3, node)
            answered = 0
            for service in services:
                srv_class = rosservice.get_service_class_by_name(service)
                proxy = rospy.ServiceProxy(service, srv_class)
                for _ in range(CALLS_PER_SERVICE):
                    req = make_request(rng, srv_class)
                    shown = str(req)[:300]
                    try:
                        resp = proxy(req)
                    except Exception:  # noqa: BLE001
                        # A value the type cannot carry (rospy refuses to serialise it) or a
                        # failed call: either way the node must still be there, checked below.
                        resp = None
                    answered += resp is not None
                    if resp is not None and hasattr(resp, "success") and not resp.success:
                        self.assertTrue(getattr(resp, "message", "x").strip(),
                                        "%s refused without a reason: %s" % (service, shown))
                    rospy.wait_for_service(service, timeout=5)  # still there
            # Most requests reach the node (the rest rospy cannot serialise).
            self.assertGreater(answered, len(services) * CALLS_PER_SERVICE // 2, node)
            rospy.loginfo("%s: %d services, %d answered calls", node, len(services), answered)
            first, _, _ = self.scans(node)
            after, level, message = self.scans(node)
            self.assertGreater(first, before, "%s: no scan during the calls" % node)
            self.assertGreater(after, first, "%s: the scan stopped after the calls" % node)
            # No fault stop (a loaded machine may make the scan late: that is not the node's fault).
            self.assertFalse(message.startswith("stopped"), "%s: %s" % (node, message))


if __name__ == "__main__":
    rospy.init_node("service_fuzz_test")
    rostest.rosrun("plc_cell", "service_fuzz_test", ServiceFuzz, sys.argv)
