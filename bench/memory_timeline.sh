#!/usr/bin/env bash
# Resident memory against the phases of a relight command: its progress lines, each with
# the seconds since the start, the resident set (MB) when the line was printed and the
# peak so far, sampled every 0.2 s from /proc. Says which phase holds the peak, which
# /usr/bin/time's one figure does not. Heavy on the stair hall: run it alone.
#   bash bench/memory_timeline.sh RELIGHT ARGS...
#   e.g. bash bench/memory_timeline.sh build/relight/relight prepare ../shared/data/staircase --force
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 RELIGHT ARGS..." >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "command: bash bench/memory_timeline.sh $*"
now() { date +%s.%N; }
"$@" >"$work/out.fifo.log" 2>&1 &
pid=$!
# The command's lines, stamped as they come.
(tail -n +1 -f "$work/out.fifo.log" --pid=$pid | while IFS= read -r line; do
    printf '%s\t%s\n' "$(now)" "$line"
done) >"$work/lines" &
reader=$!
while kill -0 $pid 2>/dev/null; do
    rss=$(awk '/^VmRSS/ {print int($2 / 1024)}' /proc/$pid/status 2>/dev/null || true)
    [ -n "$rss" ] && printf '%s\t%s\n' "$(now)" "$rss" >>"$work/rss"
    sleep 0.2
done
wait $pid && rc=0 || rc=$?
wait $reader 2>/dev/null || true
touch "$work/rss"
# Merge by time: each line with the last sample before it and the peak up to it.
sort -m -t $'\t' -k1,1n <(awk -F'\t' '{print $1 "\tS\t" $2}' "$work/rss") \
    <(awk -F'\t' '{print $1 "\tL\t" substr($0, length($1) + 2)}' "$work/lines") |
    awk -F'\t' 'NR == 1 {t0 = $1}
        $2 == "S" {rss = $3; if (rss > peak) peak = rss; next}
        {printf "%7.1f s  rss %6d MB  peak %6d MB  %s\n", $1 - t0, rss, peak, substr($3, 1, 110)}
        END {printf "peak resident memory: %d MB\n", peak}'
exit $rc
