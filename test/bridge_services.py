"""Shared by the bridges' rostests (fatek_bridge, tri_bridge): the services plc_node and the
bridges have in common, and a write that waits for the bridge to be connected."""
import time

import rospy
from std_srvs.srv import SetBool, Trigger

from plc_cell.srv import ForceDiscrete, ReadMemory, ReleaseDiscrete, WriteMemory


def connect_services(cls, ns):
    """Waits for the node's services under ns and puts their proxies on the test class."""
    for s in ["write", "set_run_mode", "recover", "read", "force", "release"]:
        rospy.wait_for_service(ns + s, timeout=30)
    cls.write = rospy.ServiceProxy(ns + "write", WriteMemory)
    cls.set_run = rospy.ServiceProxy(ns + "set_run_mode", SetBool)
    cls.recover = rospy.ServiceProxy(ns + "recover", Trigger)
    cls.read = rospy.ServiceProxy(ns + "read", ReadMemory)
    cls.force = rospy.ServiceProxy(ns + "force", ForceDiscrete)
    cls.release = rospy.ServiceProxy(ns + "release", ReleaseDiscrete)


def write_ok(write, io, address, values, timeout):
    """The bridge may still be connecting: retries the write until it goes through, waiting
    on the next ~io message (io: a Latest) between tries; the last reply."""
    deadline = time.monotonic() + timeout
    while True:
        r = write(address, values)
        if r.success or time.monotonic() > deadline:
            return r
        io.wait_for(lambda m: True, timeout=1.0)
