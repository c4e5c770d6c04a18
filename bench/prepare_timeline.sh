#!/usr/bin/env bash
# A relight command's timeline: each line it prints, stamped with the wall-clock seconds since
# the start, and its resident memory sampled every half second; then the peak. It shows where
# a time budget's phases begin and end, which the phase times alone do not (a phase that ends
# past its share's end, a wait between two phases).
#   bash bench/prepare_timeline.sh OUT RELIGHT_BINARY ARGS...
# e.g. bash bench/prepare_timeline.sh /tmp/stair ./build/relight/relight prepare \
#          ../shared/data/staircase --force --cache /tmp/stair.bin
# writes OUT.lines ("seconds  line") and OUT.mem ("seconds MB"), and prints both summaries.
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: bash bench/prepare_timeline.sh OUT RELIGHT_BINARY ARGS..." >&2
    exit 2
fi
out=$1
shift
[ -x "$1" ] || { echo "prepare_timeline.sh: $1 is not an executable" >&2; exit 2; }
echo "command: bash bench/prepare_timeline.sh $out $*"
t0=$(date +%s.%N)
stamp() {
    python3 -u -c '
import sys, time
t0 = float(sys.argv[1])
for line in sys.stdin:
    print("%6.1f  %s" % (time.time() - t0, line.rstrip()))' "$t0"
}
"$@" > >(stamp >"$out.lines") 2>&1 &
pid=$!
: >"$out.mem"
while kill -0 "$pid" 2>/dev/null; do
    rss=$(awk '/VmRSS/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
    [ -n "$rss" ] && awk -v t0="$t0" -v kb="$rss" -v now="$(date +%s.%N)" \
        'BEGIN { printf "%6.1f %d\n", now - t0, kb / 1024 }' >>"$out.mem"
    sleep 0.5
done
status=0
wait "$pid" || status=$?
sleep 0.2  # the stamping filter's last lines
cat "$out.lines"
awk 'BEGIN { m = 0 } $2 > m { m = $2; t = $1 } END { printf "peak %d MB at %.1f s\n", m, t }' \
    "$out.mem"
exit "$status"
