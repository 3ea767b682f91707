"""Shared by the rostests: the latest message of a topic, and a blocking wait for a
condition on it (event-driven, bounded by a time-out; never a sleep)."""
import threading
import time

import rospy


class Latest(object):
    """Keeps the latest message of a topic; a test blocks until a condition holds on it."""

    def __init__(self, topic, msg_type, timeout=20.0):
        self.msg = None
        self.timeout = timeout
        self.cond = threading.Condition()
        self.sub = rospy.Subscriber(topic, msg_type, self._cb)

    def _cb(self, msg):
        with self.cond:
            self.msg = msg
            self.cond.notify_all()

    def wait_for(self, pred, timeout=None):
        """The first message for which pred holds, or the last one seen at the time-out."""
        deadline = time.monotonic() + (self.timeout if timeout is None else timeout)
        with self.cond:
            while self.msg is None or not pred(self.msg):
                left = deadline - time.monotonic()
                if left <= 0:
                    return self.msg
                self.cond.wait(left)
            return self.msg


def wait_until(cond, pred, timeout):
    """Blocks until pred() holds (checked under cond, again whenever cond is notified);
    False if it still does not at the time-out."""
    deadline = time.monotonic() + timeout
    with cond:
        while not pred():
            left = deadline - time.monotonic()
            if left <= 0:
                return False
            cond.wait(left)
        return True
