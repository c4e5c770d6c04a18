#!/usr/bin/env bash
# Inserting a lamp with `relight render`: two relight binaries alternated on every bundled
# scene's virtual-lamp edits (per-pixel display, no cache, as a user's first render), so
# that the pair of figures of each row comes from the same minute of a shared machine.
# Prints, per run: the insertion's time (the solver's update and the vertices' light), the
# whole edit's time, the process's CPU seconds, and the score against the scene's truth.
#   bash bench/insert_lamp.sh OLD_RELIGHT NEW_RELIGHT [ROUNDS] [WORK_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1
new=$2
rounds=${3:-2}
work=${4:-$(mktemp -d)}
mkdir -p "$work"
echo "command: bash bench/insert_lamp.sh $*"
edits="room:virtual_light_only room:virtual_light_and_box room-multi:virtual_light_only
room-multi:virtual_light_and_box cornell:virtual_light_only courtyard:night_lamp"
printf '%-5s %-5s %-34s %9s %8s %8s %s\n' round bin edit insert_s edit_s cpu_s "rel_rmse changed"
for round in $(seq "$rounds"); do
    for bin in old new; do
        relight=$old
        [ "$bin" = new ] && relight=$new
        for se in $edits; do
            scene=${se%%:*}
            edit=${se##*:}
            out=$work/$bin-$scene-$edit.exr
            log=$work/$bin-$scene-$edit.log
            /usr/bin/time -f "cpu %U %S" "$relight" render "data/$scene" \
                --edit "data/$scene/edits/$edit.json" -o "$out" --no-cache >"$log" 2>&1
            insert=$(grep -oE "^inserted light .*, [0-9.]+ s$" "$log" | grep -oE "[0-9.]+ s$" |
                head -1 | tr -d ' s')
            whole=$(grep -oE "edit [0-9.]+ s" "$log" | tr -dc '0-9.')
            cpu=$(awk '/^cpu /{printf "%.1f", $2 + $3}' "$log")
            score=$("$relight" eval "data/$scene" "$edit" "$out" | head -2 | awk '{print $2}' |
                tr '\n' ' ')
            printf '%-5s %-5s %-34s %9s %8s %8s %s\n' "$round" "$bin" "$scene/$edit" \
                "${insert:-n/a}" "$whole" "$cpu" "$score"
        done
    done
done
