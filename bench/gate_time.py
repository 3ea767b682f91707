#!/usr/bin/env python3
"""How long a change's gate takes (docs/performance.md, "Online change: the gate"): for the
demo and every example with a scenario file, its cell YAML copied with a gate: section (the
scenario file, explore: 20s) and `plc_cell gate` timed on it, five times, side by side in one
run; then the demo served by `plc_cell run` for a while with no gate running and for as long
again with gates running one after another beside it, its wake latency and overruns compared.

    python3 bench/gate_time.py [--tool PATH] [--serve 10]
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "examples")
CELLS = [("demo conveyor", "conveyor/conveyor.yaml", "conveyor/conveyor.scenario.yaml"),
         ("hsc count_up_stop", "hsc/count_up_stop.yaml", "hsc/count_up_stop.scenario.yaml"),
         ("motion positioning", "motion/positioning.yaml", "motion/positioning.scenario.yaml"),
         ("oven", "oven/oven.yaml", "oven/oven.scenario.yaml"),
         ("temp adc_conditioning", "temp/adc_conditioning.yaml", "temp/adc_conditioning.scenario.yaml")]


def gated_copy(cell, scenario):
    """The cell's YAML beside the original (its program and scenario resolve there), its gate: the scenario."""
    src = os.path.join(EXAMPLES, cell)
    text = open(src).read()
    text = re.sub(r"(?ms)^gate:\n(  .*\n)*", "", text)  # the demo's own gate is replaced by the same one
    text += "gate:\n  scenarios: [%s]\n  explore: 20s\n" % os.path.abspath(os.path.join(EXAMPLES, scenario))
    path = os.path.join(os.path.dirname(src), ".gate_time_" + os.path.basename(src))
    with open(path, "w") as f:
        f.write(text)
    return path


def time_gate(tool, path, runs=5):
    times = []
    for _ in range(runs):
        t0 = time.monotonic()
        p = subprocess.run([tool, "gate", path, "--json"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=300)
        times.append(time.monotonic() - t0)
        if p.returncode not in (0, 1):
            sys.exit("plc_cell gate %s failed: %s" % (path, p.stderr.decode()[-2000:]))
    verdict = "pass" if p.returncode == 0 else "fail"
    return statistics.median(times), max(times), verdict


def serve(tool, seconds, gate_path=None):
    """plc_cell run's summary after `seconds`, with gates one after another beside it if gate_path."""
    run = subprocess.Popen([tool, "run", "--config", os.path.join(EXAMPLES, "conveyor", "conveyor.yaml"),
                            "--duration", "%ds" % seconds], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    gates = 0
    deadline = time.monotonic() + seconds
    while gate_path and time.monotonic() < deadline - 0.5:
        subprocess.run([tool, "gate", gate_path, "--json"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        gates += 1
    _, err = run.communicate(timeout=seconds + 30)
    line = [l for l in err.decode().splitlines() if " scans, cycle avg" in l]
    return (line[0] if line else err.decode()[-500:]), gates


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tool", default=shutil.which("plc_cell") or "plc_cell")
    ap.add_argument("--serve", type=int, default=10, help="seconds of each served run")
    args = ap.parse_args()
    made = []
    try:
        print("%-24s %10s %10s  %s" % ("cell", "median s", "max s", "verdict"))
        for name, cell, scenario in CELLS:
            path = gated_copy(cell, scenario)
            made.append(path)
            med, worst, verdict = time_gate(args.tool, path)
            print("%-24s %10.3f %10.3f  %s" % (name, med, worst, verdict))
        print()
        quiet, _ = serve(args.tool, args.serve)
        busy, gates = serve(args.tool, args.serve, made[0])
        print("demo served %d s, no gate:        %s" % (args.serve, quiet))
        print("demo served %d s, %3d gates beside: %s" % (args.serve, gates, busy))
    finally:
        for p in made:
            os.remove(p)


if __name__ == "__main__":
    main()
