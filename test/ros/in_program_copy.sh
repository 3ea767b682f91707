#!/bin/bash
# launch-prefix of a plc_node whose ~load_program a test calls: the node runs on a copy of
# its cell's program in a folder of its own, which the change service rewrites and logs
# beside (docs/online-change.md), so the package's files are never touched. $1 is the
# program to copy; the rest is the node's command line.
set -e
program=$1
shift
dir=$(mktemp -d /tmp/plc_node_program.XXXXXX)
cp "$program" "$dir/"
exec "$@" "_program:=$dir/$(basename "$program")"
