#!/usr/bin/env bash
# Every edit of a scene scored (`relight eval` against its Cycles truth) with the default
# per-pixel display, the ratio map of ../shared/seeds/000 (Eq. 3, `--display ratio-map`) and
# Wen et al.'s unoccluded E(n) of ../shared/seeds/002 (Eq. 13, `--display wen`): one
# prepared cache per scene (the same preparation serves every display).
#   bash bench/display_modes.sh [SCENE_DIR...]     (default: data/courtyard data/window_room)
set -euo pipefail
cd "$(dirname "$0")/.."
relight=${RELIGHT:-./build/relight/relight}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(data/courtyard data/window_room)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "command: bash bench/display_modes.sh ${*:-}"
printf '%-28s %-10s %10s %10s %8s\n' edit display rel_rmse changed edit_s
for scene in "${scenes[@]}"; do
    name=$(basename "$scene")
    for e in "$scene"/edits/*.json; do
        edit=$(basename "$e" .json)
        for display in pixel ratio-map wen; do
            out="$work/$name-$edit-$display.exr"
            "$relight" render "$scene" --edit "$e" -o "$out" --display "$display" \
                --cache "$work/$name.bin" --report "$work/r.json" >/dev/null 2>"$work/log" ||
                { echo "$name/$edit $display: render failed"; tail -3 "$work/log"; continue; }
            score=$("$relight" eval "$scene" "$edit" "$out" 2>&1)
            python3 - "$name/$edit" "$display" "$work/r.json" "$score" <<'PY'
import json, re, sys
edit, display, report, text = sys.argv[1:5]
r = json.load(open(report))
def num(key):
    m = re.search(key + r"[^0-9.]*([0-9.]+)", text)
    return float(m.group(1)) if m else float("nan")
t = r.get("time_s", {}).get("edit", float("nan"))
print(f"{edit:28s} {display:10s} {num('rel_rmse'):10.4f} {num('changed'):10.4f} {t:8.2f}")
PY
        done
    done
done
