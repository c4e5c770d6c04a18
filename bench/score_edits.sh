#!/usr/bin/env bash
# Every edit of the bundled scenes (and of any scene folders given), relit with each
# display mode (ratio, confidence, pixel: relight/prepared.h) and scored against the path-traced truth (spec metric, `relight eval`):
# rel_rmse and changed_rel_rmse side by side. An edit the engine refuses is listed as refused.
# Prepares each scene once per mode (a cache per scene and mode in the work folder).
#   bash bench/score_edits.sh [SCENE_DIR ...]      (default: data/room data/cornell data/room-multi)
# A scene folder without truth/ (a tessellated copy) may link its original's truth/.
set -euo pipefail
cd "$(dirname "$0")/.."
relight=${RELIGHT:-./build/relight/relight}  # RELIGHT=path: another binary
read -r -a extra <<<"${RELIGHT_ARGS:-}"  # RELIGHT_ARGS="...": more options for render
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(data/room data/cornell data/room-multi)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "command: ${RELIGHT_ARGS:+RELIGHT_ARGS=\"$RELIGHT_ARGS\" }bash bench/score_edits.sh ${*:-}"
printf '%-20s %-24s %17s %17s %17s %17s\n' scene edit "ratio" "confidence" "pixel" \
    "photo (unedited)"
for dir in "${scenes[@]}"; do
    name=$(basename "$dir")
    for file in "$dir"/edits/*.json; do
        edit=$(basename "$file" .json)
        [ -f "$dir/truth/$edit.exr" ] || continue
        row=()
        for mode in ratio confidence pixel; do
            out="$work/$name-$edit-$mode.exr"
            if "$relight" render "$dir" --edit "$file" -o "$out" --display "$mode" \
                --cache "$work/$name-$mode.bin" "${extra[@]}" >"$work/log" 2>&1; then
                row+=("$("$relight" eval "$dir" "$edit" "$out" |
                    awk '/^rel_rmse/ {r = $2} /^changed_rel_rmse/ {c = $2} END {print r " / " c}')")
            else
                row+=("refused")
            fi
        done
        photo=$("$relight" eval "$dir" "$edit" "$dir/photo.exr" |
            awk '/^rel_rmse/ {r = $2} /^changed_rel_rmse/ {c = $2} END {print r " / " c}')
        printf '%-20s %-24s %17s %17s %17s %17s\n' "$name" "$edit" "${row[0]}" "${row[1]}" \
            "${row[2]}" "$photo"
    done
done
