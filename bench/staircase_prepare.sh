#!/usr/bin/env bash
# The staircase (or any scene folder) prepared once, with its phase times and peak memory,
# then every edit rendered from that preparation and scored against the truth (`relight
# eval`): the figures of issue 30's "bounded phases" table. Heavy (minutes, GBs): run it
# under `flock /tmp/relight-heavy.lock`.
#   bash bench/staircase_prepare.sh [SCENE_DIR] [WORK_DIR]   (default ../shared/data/staircase)
# RELIGHT=path picks another binary; RELIGHT_ARGS="..." adds preparation options;
# EDITS="a b ..." scores those edits only (the removal and insertions take minutes each on
# the staircase).
set -euo pipefail
cd "$(dirname "$0")/.."
relight=${RELIGHT:-./build/relight/relight}
read -r -a extra <<<"${RELIGHT_ARGS:-}"
dir=${1:-../shared/data/staircase}
work=${2:-$(mktemp -d)}
mkdir -p "$work"
cache="$work/prepared.bin"
echo "command: ${RELIGHT_ARGS:+RELIGHT_ARGS=\"$RELIGHT_ARGS\" }bash bench/staircase_prepare.sh $dir $work"
echo "relight prepare $dir --force --cache $cache ${extra[*]}"
/usr/bin/time -v "$relight" prepare "$dir" --force --cache "$cache" "${extra[@]}" \
    2>"$work/prepare.err" >"$work/prepare.out" || { cat "$work/prepare.err"; exit 1; }
grep -v '^\s*\(Command\|User\|System\|Percent\|Average\|Major\|Minor\|Volun\|Invol\|Swaps\|File\|Socket\|Signals\|Page\|Exit\|Maximum resident\)' \
    "$work/prepare.err" | grep -v '^\s*Elapsed' || true
cat "$work/prepare.out"
awk '/Elapsed \(wall/ {w = $NF} /User time/ {u = $NF} /System time/ {y = $NF}
     /Maximum resident/ {m = $NF}
     END {printf "prepare %s wall, %.1f s CPU (user + system), peak %d MB\n", w, u + y, m / 1024}' \
    "$work/prepare.err"
echo
echo "edits (relight render --cache, then relight eval):"
for file in "$dir"/edits/*.json; do
    edit=$(basename "$file" .json)
    [ -f "$dir/truth/$edit.exr" ] || continue
    [ -z "${EDITS:-}" ] || [[ " $EDITS " == *" $edit "* ]] || continue
    out="$work/$edit.exr"
    if "$relight" render "$dir" --edit "$file" -o "$out" --cache "$cache" "${extra[@]}" \
        >"$work/render.log" 2>&1; then
        printf '%-20s %s\n' "$edit" "$("$relight" eval "$dir" "$edit" "$out" |
            awk '/^rel_rmse/ {r = $2} /^changed_rel_rmse/ {c = $2} END {print r " / " c}')"
    else
        printf '%-20s refused: %s\n' "$edit" "$(tail -1 "$work/render.log")"
    fi
done
