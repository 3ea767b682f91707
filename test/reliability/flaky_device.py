#!/usr/bin/python3
"""rostest fixture: a TCP device that misbehaves on demand, for the bridges' rostests.
It listens on ~listen_port and forwards to an upstream slave: ~upstream (HOST:PORT), or a
`plc_cell run --fatek-tcp` it starts itself with ~fatek_program. Services (std_srvs/Trigger):
~normal (forward), ~silent (swallow requests, answer nothing), ~garbage (answer every
request with random bytes, fixed seed), ~vanish (close every connection and the listening
socket: connections are refused until ~normal)."""
import os
import random
import select
import socket
import subprocess
import sys
import threading

import rospy
from std_srvs.srv import Trigger, TriggerResponse


sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), ".."))
from tool_path import find_tool  # noqa: E402


class Device(object):
    def __init__(self, port, upstream):
        self.port, self.upstream = port, upstream
        self.mode = "normal"
        self.lock = threading.Lock()
        self.conns = []
        self.listener = None
        self.rng = random.Random(1234)
        self.listen()

    def listen(self):
        s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        s.bind(("127.0.0.1", self.port))
        s.listen(8)
        self.listener = s
        threading.Thread(target=self.accept_loop, args=(s,), daemon=True).start()

    def accept_loop(self, s):
        while True:
            try:
                c, _ = s.accept()
            except OSError:
                return  # closed by vanish
            threading.Thread(target=self.pump, args=(c,), daemon=True).start()

    def pump(self, c):
        try:
            up = socket.create_connection(self.upstream, timeout=2)
        except OSError:
            c.close()
            return
        with self.lock:
            self.conns += [c, up]
        try:
            while True:
                r, _, _ = select.select([c, up], [], [], 0.1)
                for s in r:
                    data = s.recv(4096)
                    if not data:
                        return
                    mode = self.mode
                    if s is c and mode == "normal":
                        up.sendall(data)
                    elif s is c and mode == "garbage":
                        c.sendall(bytes(self.rng.randrange(256) for _ in range(len(data))))
                    elif s is up and mode == "normal":
                        c.sendall(data)
                    # silent: requests are swallowed; late answers from upstream are dropped
        except OSError:
            return
        finally:
            for s in (c, up):
                try:
                    s.close()
                except OSError:
                    pass

    def set_mode(self, mode):
        with self.lock:
            old, self.mode = self.mode, mode
            if mode == "vanish":
                self.listener.close()
                for s in self.conns:
                    try:
                        s.shutdown(socket.SHUT_RDWR)
                    except OSError:
                        pass
                self.conns = []
        if old == "vanish" and mode != "vanish":
            self.listen()
        return TriggerResponse(success=True, message=mode)


def main():
    rospy.init_node("flaky_device")
    port = int(rospy.get_param("~listen_port"))
    child = None
    program = rospy.get_param("~fatek_program", "")
    if program:
        child = subprocess.Popen([find_tool(), "run", "--program", program, "--fatek-tcp", "127.0.0.1:0"],
                                 stderr=subprocess.PIPE, universal_newlines=True)
        for line in child.stderr:  # "plc_cell run: serving FATEK TCP 127.0.0.1:PORT station 1"
            if "serving FATEK TCP" in line:
                upstream = ("127.0.0.1", int(line.split("127.0.0.1:")[1].split()[0]))
                break
        threading.Thread(target=lambda: [None for _ in child.stderr], daemon=True).start()
    else:
        host, p = rospy.get_param("~upstream").rsplit(":", 1)
        upstream = (host, int(p))
    dev = Device(port, upstream)
    for mode in ("normal", "silent", "garbage", "vanish"):
        rospy.Service("~" + mode, Trigger, lambda req, m=mode: dev.set_mode(m))
    rospy.loginfo("flaky_device: 127.0.0.1:%d -> %s:%d", port, upstream[0], upstream[1])
    rospy.spin()
    if child:
        child.terminate()
        child.wait(timeout=5)
    return 0


if __name__ == "__main__":
    sys.exit(main())
