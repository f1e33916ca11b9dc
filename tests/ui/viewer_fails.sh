#!/bin/bash
# Runs the viewer under xvfb-run and passes when the viewer itself exits with status 2 and prints PATTERN.
# The viewer's own status is read, not xvfb-run's: after a command that exits within a fraction of a second,
# xvfb-run may fail to clean up its temporary directory and exit with a status of its own.
# Usage: viewer_fails.sh XVFB_RUN PATTERN SONARSIM ARGS...
xvfb=$1 pattern=$2
shift 2
out=$("$xvfb" -a -s "-screen 0 1280x800x24" bash -c '"$@" 2>&1; echo "viewer exit status $?"' _ "$@" 2>&1)
echo "$out"
grep -qx "viewer exit status 2" <<< "$out" && grep -qF -- "$pattern" <<< "$out"
