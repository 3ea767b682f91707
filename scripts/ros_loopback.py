#!/usr/bin/python3
"""ROS on this machine only: the tests, the doc tests and `make demo` run every node and the
master on loopback, so they must not depend on the machine's own hostname resolving.

ROS names the master and each node by ROS_IP, else ROS_HOSTNAME, else the hostname: in a
minimal container whose /etc/hosts lacks its hostname, every node fails with "Unable to
contact my own server". So where neither ROS_HOSTNAME nor ROS_IP is set, ROS_HOSTNAME is
localhost.

As a program (make demo), it prints the shell line that sets it (`eval "$(...)"`), and when
the name ROS would use still cannot reach this machine it prints a hint on stderr and exits 2,
before roslaunch fails with a stack trace."""
import os
import socket
import sys


def loopback_env(env):
    """env, with ROS_HOSTNAME=localhost when neither ROS_HOSTNAME nor ROS_IP is set."""
    out = dict(env)
    if not out.get("ROS_HOSTNAME") and not out.get("ROS_IP"):
        out["ROS_HOSTNAME"] = "localhost"
    return out


def unreachable(env):
    """Why the master could not reach itself under env's names, or None."""
    host = env.get("ROS_IP") or env.get("ROS_HOSTNAME") or socket.gethostname()
    var = "ROS_IP" if env.get("ROS_IP") else "ROS_HOSTNAME" if env.get("ROS_HOSTNAME") else "the hostname"
    try:
        addrs = socket.getaddrinfo(host, None, type=socket.SOCK_STREAM)
    except socket.gaierror as e:
        return "%s %r does not resolve on this machine (%s)" % (var, host, e.strerror)
    # The master listens on every interface and calls itself back by this name.
    for family, _, _, _, sockaddr in addrs:
        try:
            with socket.socket(family, socket.SOCK_STREAM) as srv:
                srv.bind(("::" if family == socket.AF_INET6 else "0.0.0.0", 0))
                srv.listen(1)
                with socket.create_connection((sockaddr[0], srv.getsockname()[1]), timeout=2):
                    return None
        except OSError:
            continue
    return "%s %r resolves to %s, which this machine does not answer on" % (
        var, host, ", ".join(sorted({a[4][0] for a in addrs})))


def main():
    env = loopback_env(os.environ)
    why = unreachable(env)
    if why:
        sys.stderr.write(
            "ROS cannot reach its own master: %s.\n"
            "For a cell on this machine only:  export ROS_HOSTNAME=localhost  (and unset ROS_IP)\n"
            "To reach it from other machines:  export ROS_IP=<this machine's address>\n" % why)
        return 2
    if env.get("ROS_HOSTNAME") != os.environ.get("ROS_HOSTNAME"):
        print("export ROS_HOSTNAME=%s" % env["ROS_HOSTNAME"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
