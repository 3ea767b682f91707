#!/usr/bin/python3
"""Runs the plc_cell benchmarks (make bench) and prints a summary table.

  bench_scan      Google Benchmark: the 10,000-instruction ladder through the
                  parser, the interpreter, a full Plc scan and the same ladder
                  compiled to C++; repeated, medians reported.
  bench_realtime  RealTimeLoop at 1 ms on the conveyor program: wake latency
                  percentiles, cycle time, overruns.
  bench_temp      (when built) 64 temperature channels + 16 FUN86 loops against
                  a 1 ms scan.
  bench_line      (when built) chains of 10, 100 and 1,000 demo-like cells on one
                  virtual clock, as plc_cell sim runs them (cell by cell) and instant
                  by instant, beside the same cells unwired and with no line;
                  and, in a process of its own, the memory of 1,000 cells.

The targets checked are those of docs/performance.md. The exit status is 0 when
both benchmarks ran, whatever the figures: the machine decides those.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from process_tree import exit_on_sigterm  # noqa: E402

TARGET_NS_PER_INSTR = 5.0
TARGET_SCAN_US = 50.0
TARGET_P99_US = 200.0
TARGET_LINE_X = {100: 100.0, 1000: 10.0}  # cells in a chain: x real time in plc_cell sim


def find_binary(ws, name):
    """catkin puts package executables in devel/lib/<package>/."""
    for path in (os.path.join(ws, "devel", "lib", "plc_cell", name),
                 os.path.join(ws, "build", "plc_cell", name),
                 os.path.join(ws, "build", name)):
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    sys.exit("run_bench: %s not found under %s (is libbenchmark-dev installed? "
             "then rerun make build)" % (name, ws))


def run_scan_bench(binary, repetitions, min_time):
    """Runs bench_scan, returns {benchmark name: {field: median}}."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as f:
        out = f.name
    try:
        cmd = [binary,
               "--benchmark_repetitions=%d" % repetitions,
               "--benchmark_report_aggregates_only=true",
               "--benchmark_min_time=%g" % min_time,
               "--benchmark_out=%s" % out,
               "--benchmark_out_format=json"]
        print("$ " + " ".join(cmd), flush=True)
        subprocess.check_call(cmd, stdin=subprocess.DEVNULL)
        with open(out) as f:
            data = json.load(f)
    finally:
        os.unlink(out)
    medians, errors = {}, []
    for b in data["benchmarks"]:
        if b.get("error_occurred"):
            errors.append("%s: %s" % (b["name"], b.get("error_message", "")))
            continue
        if b.get("aggregate_name") != "median":
            continue
        medians[b["run_name"]] = b
    if errors:
        sys.exit("run_bench: bench_scan failed:\n  " + "\n  ".join(errors))
    return medians


def to_us(b):
    """Real time of one iteration in microseconds."""
    scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}[b.get("time_unit", "ns")]
    return b["real_time"] * scale


def cpu_us(b):
    scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}[b.get("time_unit", "ns")]
    return b["cpu_time"] * scale


def run_realtime_bench(binary, seconds):
    cmd = [binary, str(seconds)]
    print("$ " + " ".join(cmd), flush=True)
    text = subprocess.run(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          universal_newlines=True, timeout=seconds + 300).stdout
    sys.stdout.write(text)
    figures = {}
    for line in text.splitlines():
        key, _, value = line.partition(" ")
        figures[key] = value
    return figures


def verdict(ok):
    return "met" if ok else "MISSED"


def line_rows(ws, repetitions, min_time):
    """bench_line's figures (docs/performance.md, "Lines of cells"), side by side."""
    binary = os.path.join(ws, "devel", "lib", "plc_cell", "bench_line")
    if not os.path.isfile(binary):
        return []
    print()
    b = run_scan_bench(binary, repetitions, min_time)
    rows = [("Demo cell alone, per scan", "%.0f ns" % b["BM_DemoAlone"]["ns_per_cell_scan"], "")]
    busy = (b["BM_BusyWires/16"]["ns_per_instant"] - b["BM_BusyWires/0"]["ns_per_instant"]) / 16
    rows.append(("A wire changing at every scan, per change", "%.1f ns" % busy, ""))
    for n in (10, 100, 1000):
        cells = b["BM_Cells/%d" % n]["ns_per_cell_scan"]
        unwired = b["BM_Unwired/%d" % n]["ns_per_cell_scan"]
        chain = b["BM_Chain/%d" % n]
        sim = b["BM_ChainSim/%d" % n]
        x = sim["x_real_time"]
        target = TARGET_LINE_X.get(n)
        note = ">= %gx: %s" % (target, verdict(x >= target)) if target else ""
        rows.append(("%d cells: no line / unwired / chain, instant by instant, per cell-scan" % n,
                     "%.0f / %.0f / %.0f ns" % (cells, unwired, chain["ns_per_cell_scan"]), ""))
        rows.append(("  chain of %d instant by instant (a line's cases)" % n, "%.1fx real time" % chain["x_real_time"], ""))
        rows.append(("  chain of %d in plc_cell sim (cell by cell), per cell-scan" % n,
                     "%.0f ns, %.1fx real time" % (sim["ns_per_cell_scan"], x), note))
    cmd = [binary, "--memory", "1000"]
    print("$ " + " ".join(cmd), flush=True)
    text = subprocess.run(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          universal_newlines=True, timeout=600).stdout
    sys.stdout.write(text)
    mem = dict(line.split(" ", 1) for line in text.splitlines() if " " in line)
    rows.append(("Memory per cell (1,000 cells): resident / heap",
                 "%.0f / %.0f KiB" % (float(mem["resident_bytes_per_cell"]) / 1024,
                                      float(mem["heap_bytes_per_cell"]) / 1024), ""))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workspace", required=True, help="catkin workspace, e.g. .build/ws")
    ap.add_argument("--repetitions", type=int, default=5)
    ap.add_argument("--min-time", type=float, default=0.5, help="seconds per repetition")
    ap.add_argument("--realtime-seconds", type=float, default=10)
    args = ap.parse_args()
    exit_on_sigterm()  # a SIGTERM ends the running benchmark too (subprocess kills it on the way out)
    ws = os.path.abspath(args.workspace)

    scan = run_scan_bench(find_binary(ws, "bench_scan"), args.repetitions, args.min_time)
    print()
    rt = run_realtime_bench(find_binary(ws, "bench_realtime"), args.realtime_seconds)

    # per_instr is an inverted rate over CPU time: seconds per instruction.
    interp_ns = scan["BM_Interpreter"]["per_instr"] * 1e9
    plc_ns = scan["BM_PlcScan"]["per_instr"] * 1e9
    compiled_ns = scan["BM_CompiledLadder"]["per_instr"] * 1e9
    plc_us = cpu_us(scan["BM_PlcScan"])
    p99 = float(rt.get("wake_latency_p99_us", "nan"))

    rows = [
        ("Plc::scan, 10,000-instr ladder", "%.1f us/scan" % plc_us,
         "<= %g us: %s" % (TARGET_SCAN_US, verdict(plc_us <= TARGET_SCAN_US))),
        ("  per instruction", "%.2f ns" % plc_ns,
         "<= %g ns: %s" % (TARGET_NS_PER_INSTR, verdict(plc_ns <= TARGET_NS_PER_INSTR))),
        ("Interpreter only, per instruction", "%.2f ns" % interp_ns,
         "<= %g ns: %s" % (TARGET_NS_PER_INSTR, verdict(interp_ns <= TARGET_NS_PER_INSTR))),
        ("Compiled C++ ladder, per instruction", "%.3f ns" % compiled_ns, "baseline"),
        ("Interpreter / compiled ratio", "%.0fx" % (interp_ns / compiled_ns), ""),
        ("Scan overhead (1-network program)", "%.2f us" % cpu_us(scan["BM_PlcScanOverhead"]), ""),
        ("Parse 10,000-instr ladder", "%.2f ms" % (cpu_us(scan["BM_Parse"]) / 1e3),
         "%.0f ns/instr" % (scan["BM_Parse"]["per_instr"] * 1e9)),
        ("1 ms loop, wake latency p50/p90", "%s / %s us" % (rt.get("wake_latency_p50_us"),
                                                             rt.get("wake_latency_p90_us")), ""),
        ("  p99", "%s us" % rt.get("wake_latency_p99_us"),
         "<= %g us: %s" % (TARGET_P99_US, verdict(p99 <= TARGET_P99_US))),
        ("  p99.9 / max", "%s / %s us" % (rt.get("wake_latency_p99.9_us"),
                                           rt.get("wake_latency_max_us")), ""),
        ("  cycle time avg / max", "%s / %s us" % (rt.get("cycle_avg_us"), rt.get("cycle_max_us")), ""),
        ("  scans / overruns", "%s / %s" % (rt.get("scans"), rt.get("overruns")),
         rt.get("sched", "")),
    ]
    # Subsystem benchmarks: bench_temp (docs/analog-and-temperature.md).
    temp_bin = os.path.join(ws, "devel", "lib", "plc_cell", "bench_temp")
    if os.path.isfile(temp_bin):
        print()
        t = run_scan_bench(temp_bin, args.repetitions, args.min_time)
        base_ns = cpu_us(t["BM_TwoPlcs_Baseline"]) * 1e3
        full_ns = cpu_us(t["BM_TwoPlcs_64Channels_16Pid"]) * 1e3
        pct = (full_ns - base_ns) / 1e6 * 100
        rows.append(("64 temp channels + 16 PID loops", "%.0f ns/scan" % (full_ns - base_ns),
                     "%.3f %% of 1 ms, < 2 %%: %s" % (pct, verdict(pct < 2.0))))
    rows += line_rows(ws, args.repetitions, args.min_time)
    print()
    print("== plc_cell benchmark summary (medians of %d repetitions; CPU time; %d CPUs)"
          % (args.repetitions, os.cpu_count() or 0))
    w0 = max(len(r[0]) for r in rows)
    w1 = max(len(r[1]) for r in rows)
    for name, value, note in rows:
        print("  %-*s  %*s  %s" % (w0, name, w1, value, note))
    try:
        print("  load average at the end: %.2f %.2f %.2f" % os.getloadavg())
    except OSError:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
