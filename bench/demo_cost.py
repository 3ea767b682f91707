#!/usr/bin/python3
"""The demo's cost per scan in `plc_cell sim`, for one or more build trees side by side.

For each workspace (a catkin workspace with a built devel/ tree):
  - the CPU (user) time of `--seconds` virtual seconds of the demo conveyor, native
    engine, over --runs runs taken in turn with the other workspaces' runs, so that the
    machine's drift falls on all of them alike;
  - the instructions a scan, counted under valgrind's callgrind: the count of a 40 s run
    less that of a 10 s run, over the 30,000 scans between. Exact and the same on every
    run, so it compares two builds when the time is too noisy to.

    bench/demo_cost.py [--runs 10] [--seconds 600] [--no-instructions] WORKSPACE [WORKSPACE ...]
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, '..', 'scripts'))
from process_tree import exit_on_sigterm  # noqa: E402

CONFIG = os.path.join(HERE, '..', 'examples', 'conveyor', 'conveyor.yaml')
PERIOD_S = 0.001  # the demo's scan period


def command(ws, seconds):
    tool = os.path.join(ws, 'devel', 'lib', 'plc_cell', 'plc_cell')
    return [tool, 'sim', '--config', CONFIG, '--duration', '%gs' % seconds, '--engine', 'native']


def environment(ws):
    env = dict(os.environ)
    env['LD_LIBRARY_PATH'] = os.path.join(ws, 'devel', 'lib') + ':' + env.get('LD_LIBRARY_PATH', '')
    return env


def user_time(ws, seconds):
    proc = subprocess.Popen(command(ws, seconds), env=environment(ws), stdout=subprocess.DEVNULL)
    try:
        _, status, usage = os.wait4(proc.pid, 0)
    except BaseException:  # Ctrl-C or SIGTERM of this script: the run goes too
        proc.kill()
        proc.wait()
        raise
    if status != 0:
        sys.exit('%s: the demo run failed (status %d)' % (ws, status))
    return usage.ru_utime


def instructions(ws, seconds):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, 'callgrind.out')
        subprocess.run(['valgrind', '--tool=callgrind', '--callgrind-out-file=' + out] + command(ws, seconds),
                       env=environment(ws), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        with open(out) as f:
            for line in f:
                m = re.match(r'(?:summary|totals):\s+(\d+)', line)
                if m:
                    return int(m.group(1))
    sys.exit('%s: no instruction total in the callgrind output' % ws)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('workspaces', nargs='+')
    ap.add_argument('--runs', type=int, default=10)
    ap.add_argument('--seconds', type=float, default=600)
    ap.add_argument('--no-instructions', action='store_true', help='the times only (no valgrind)')
    a = ap.parse_args()
    exit_on_sigterm()
    for ws in a.workspaces:
        if not os.path.exists(command(ws, 1)[0]):
            sys.exit('%s: no built plc_cell tool in devel/lib/plc_cell' % ws)
    times = {ws: [] for ws in a.workspaces}
    for _ in range(a.runs):
        for ws in a.workspaces:
            times[ws].append(user_time(ws, a.seconds))
    count = not a.no_instructions and shutil.which('valgrind')
    scans = a.seconds / PERIOD_S
    print('%-40s %-22s %9s %12s %10s %14s' % ('workspace', 'CPU (user), s', 'mean, s', 'virtual/CPU', 'per scan',
                                             'instructions'))
    for ws in a.workspaces:
        t = times[ws]
        mean = statistics.mean(t)
        per_scan = ''
        if count:
            per_scan = '%d' % round((instructions(ws, 40) - instructions(ws, 10)) / (30 / PERIOD_S))
        print('%-40s %-22s %9.3f %11.0fx %8.0f ns %14s' % (ws, '%.2f-%.2f' % (min(t), max(t)), mean, a.seconds / mean,
                                                          mean / scans * 1e9, per_scan))
    if not a.no_instructions and not count:
        print('(no valgrind: instructions not counted)')


if __name__ == '__main__':
    main()
