#!/usr/bin/env bash
# scripts/phase.sh NAME COMMAND: runs COMMAND (one bash command line, with pipefail) and then
# prints how long it took, on the wall clock and in CPU seconds of everything it ran:
#   == phase NAME: 412 s, 790 CPU s
# The wall time depends on what else the machine runs; the CPU seconds much less. make test
# marks its phases this way, and scripts/test_fresh.sh gathers the lines into a table
# (docs/testing.md, "The suite's own time"). Exits with COMMAND's status.
name=$1
start=$(date +%s)
bash -o pipefail -c "$2"
rc=$?
# `times`: this shell's user and system time, then its children's (as XmY.ZZZs); into a
# file, as a pipe would run it in a subshell, which has no children of its own.
tmp=$(mktemp)
times > "$tmp"
cpu=$(tail -n 1 "$tmp" | awk '{ s = 0; for (i = 1; i <= 2; i++) { split($i, a, /[ms]/); s += a[1] * 60 + a[2] } printf "%.0f", s }')
rm -f "$tmp"
echo "== phase $name: $(( $(date +%s) - start )) s, $cpu CPU s"
exit $rc
