#!/usr/bin/env bash
# Every edit of the given scenes relit with the default per-pixel display by two relight
# binaries (A: a baseline, say main's; B: this tree's) and scored by `relight eval`
# (rel_rmse / changed_rel_rmse) side by side; each binary prepares each scene once (its own
# cache). Each render runs under flock $RELIGHT_LOCK (default /tmp/relight-heavy.lock, the
# common rules' lock for runs over a minute or 2 GB; RELIGHT_LOCK= runs without it: the
# bundled scenes' renders take under a minute and 0.5 GB).
#   RELIGHT_A=/path/to/main/relight [RELIGHT_B=./build/relight/relight] \
#       bash bench/pixel_edits_ab.sh SCENE_DIR...
set -euo pipefail
cd "$(dirname "$0")/.."
a=${RELIGHT_A:?RELIGHT_A: the baseline relight binary}
b=${RELIGHT_B:-./build/relight/relight}
lock=${RELIGHT_LOCK-/tmp/relight-heavy.lock}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "command: RELIGHT_A=$a RELIGHT_B=$b bash bench/pixel_edits_ab.sh $*"
printf '%-14s %-24s %19s %19s\n' scene edit "A" "B"
score() {  # binary tag scene edit-file
    local out="$work/$2-$(basename "$3")-$(basename "$4" .json).exr"
    if ${lock:+flock "$lock"} "$1" render "$3" --edit "$4" -o "$out" \
        --cache "$work/$2-$(basename "$3").bin" >"$work/log" 2>&1; then
        "$1" eval "$3" "$(basename "$4" .json)" "$out" |
            awk '/^rel_rmse/ {r = $2} /^changed_rel_rmse/ {c = $2} END {print r " / " c}'
    else
        echo refused
    fi
}
for dir in "$@"; do
    for file in "$dir"/edits/*.json; do
        edit=$(basename "$file" .json)
        [ -f "$dir/truth/$edit.exr" ] || continue
        printf '%-14s %-24s %19s %19s\n' "$(basename "$dir")" "$edit" \
            "$(score "$a" A "$dir" "$file")" "$(score "$b" B "$dir" "$file")"
    done
done
