#!/usr/bin/env bash
# Refinement threshold against error and time: each edit below relit at each epsilon
# (prepared afresh, per-pixel display), its spec score (`relight eval`) and the preparation
# and edit times `render` prints.
#   bash bench/epsilon_sweep.sh ROOM_T16 CORNELL_T8
# with the tessellated copies made by ../shared/tools/tessellate.py (truth linked), e.g.
#   python3 ../shared/tools/tessellate.py data/room /tmp/room-t16 16 --jitter 0.002
#   python3 ../shared/tools/tessellate.py data/cornell /tmp/cornell-t8 8 --jitter 0
#   ln -sfn "$PWD/data/room/truth" /tmp/room-t16/truth; ln -sfn "$PWD/data/cornell/truth" /tmp/cornell-t8/truth
set -euo pipefail
cd "$(dirname "$0")/.."
B=${RELIGHT:-./build/relight/relight}
t16=${1:?room-t16 folder}
t8=${2:?cornell-t8 folder}
out=$(mktemp --suffix=.exr)
trap 'rm -f "$out"' EXIT
echo "command: bash bench/epsilon_sweep.sh $*"
printf '%-8s %-12s %-20s %-17s %9s %8s\n' epsilon scene edit score prepare_s edit_s
for e in 1e-4 5e-5 3e-5 2e-5; do
  for se in "data/cornell virtual_light_only" "data/cornell virtual_box" "data/room virtual_light_only" "data/room remove_table" "data/room virtual_box" "$t16 virtual_box" "$t8 virtual_light_only"; do
    set -- $se
    t=$($B render $1 --edit $1/edits/$2.json -o "$out" --no-cache --epsilon $e 2>/dev/null | grep -E "^time")
    p=$(echo "$t" | sed -E 's/.*prepare ([0-9.]+) s.*/\1/'); ed=$(echo "$t" | sed -E 's/.*edit ([0-9.]+) s.*/\1/')
    sc=$($B eval $1 $2 "$out" | awk '/^rel_rmse/ {r=$2} /^changed_rel_rmse/ {c=$2} END {print r " / " c}')
    printf '%-8s %-12s %-20s %-17s %9s %8s\n' $e $(basename $1) $2 "$sc" $p $ed
  done
done
