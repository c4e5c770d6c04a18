#!/usr/bin/env bash
# Where `relight solve` spends its time: each line it prints, stamped with the seconds since
# the command began, then the wall time, the peak memory and the machine's load. Two
# binaries (main's and a branch's) run one after the other give a comparison under the same
# load, e.g.
#   bash bench/solve_timeline.sh ../shared/data/staircase OLD_BINARY ./build/relight/relight
# Extra arguments for `relight solve` go in SOLVE_ARGS (e.g. SOLVE_ARGS="-o /tmp/s.exr").
set -euo pipefail
scene=${1:?scene folder}
shift
[ $# -gt 0 ] || set -- ./build/relight/relight
echo "command: bash bench/solve_timeline.sh $scene $* (SOLVE_ARGS=${SOLVE_ARGS:-})"
for bin in "$@"; do
  echo "== $bin solve $scene ${SOLVE_ARGS:-} (load before: $(cut -d' ' -f1-3 /proc/loadavg))"
  # stdbuf: stdout unbuffered, so that the stamps are those of the lines' printing.
  # shellcheck disable=SC2086
  /usr/bin/time -f "wall %e s, peak %M KiB" stdbuf -o0 "$bin" solve "$scene" ${SOLVE_ARGS:-} 2>&1 |
    python3 -u -c '
import sys, time
t0 = time.time()
for line in sys.stdin:
    print("%6.1f  %s" % (time.time() - t0, line.rstrip()))
'
  echo "   (load after: $(cut -d' ' -f1-3 /proc/loadavg))"
done
