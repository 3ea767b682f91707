"""Shared by the bridges' rostests: a device that misbehaves (flaky_device.py) must not
silence a bridge's /diagnostics, and the bridge must recover when the device is back."""
import rospy
from std_srvs.srv import Trigger


def misbehaving_device_keeps_reporting(test, diag, status_prefix, device_ns, data):
    """The device goes silent, answers garbage, vanishes; after each it comes back. While it
    misbehaves the bridge keeps publishing /diagnostics with ERROR or STALE and a reason; once
    it is back the status is OK again and fresh data flows. Every wait is bounded."""
    def status(m):
        return next((s for s in m.status if s.name.startswith(status_prefix)), None)

    for mode in ("normal", "silent", "garbage", "vanish"):
        rospy.wait_for_service(device_ns + mode, timeout=30)
    t0 = rospy.Time.now()
    m = diag.wait_for(lambda m: m.header.stamp > t0 and status(m) is not None and status(m).level == 0)
    test.assertTrue(m is not None and status(m) is not None and status(m).level == 0, m)
    for mode in ("silent", "garbage", "vanish"):
        test.assertTrue(rospy.ServiceProxy(device_ns + mode, Trigger)().success)
        t1 = rospy.Time.now()
        bad = diag.wait_for(lambda m: m.header.stamp > t1 and status(m) is not None and status(m).level >= 2)
        s = status(bad) if bad else None
        test.assertTrue(s is not None and s.level >= 2, "%s: no ERROR/STALE on /diagnostics: %s" % (mode, s))
        test.assertNotEqual(s.message.strip(), "", mode)
        # Still publishing while the device misbehaves: a later report, still not OK.
        t2 = bad.header.stamp
        again = diag.wait_for(lambda m: m.header.stamp > t2 and status(m) is not None)
        s2 = status(again) if again and again.header.stamp > t2 else None
        test.assertTrue(s2 is not None and s2.level >= 2, "%s: diagnostics stopped or OK too early: %s" % (mode, s2))
        test.assertTrue(rospy.ServiceProxy(device_ns + "normal", Trigger)().success)
        t3 = rospy.Time.now()
        ok = diag.wait_for(lambda m: m.header.stamp > t3 and status(m) is not None and status(m).level == 0)
        test.assertTrue(ok is not None and status(ok) is not None and status(ok).level == 0,
                        "%s: did not recover: %s" % (mode, status(ok) if ok else None))
        fresh = data.wait_for(lambda m: m.header.stamp > t3)
        test.assertTrue(fresh is not None and fresh.header.stamp > t3, "%s: no data after recovery" % mode)
