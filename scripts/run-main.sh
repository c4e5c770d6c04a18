#!/usr/bin/env bash
# README command 1: install, build, and run the main job on the bundled room: relight its
# photo for each of its edits (light changes, virtual lights and objects, a real object removed) and score each against the path-traced truth.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
mkdir -p out
relight=./build/relight/relight
printf '%-24s %9s %9s\n' edit rel_rmse "(photo)" >out/room-scores.txt
for edit in identity back_off left_off_right_double right_off_left_double colours \
    virtual_light_only virtual_box virtual_box_moved virtual_light_and_box remove_table; do
    echo "== relight render data/room --edit data/room/edits/$edit.json"
    "$relight" render data/room --edit "data/room/edits/$edit.json" -o "out/room-$edit.exr" \
        --report "out/room-$edit.json" 2>/dev/null
    "$relight" render data/room --edit "data/room/edits/$edit.json" -o "out/room-$edit.png" \
        >/dev/null 2>&1
    ours=$("$relight" eval data/room "$edit" "out/room-$edit.exr" | awk '/^rel_rmse/ {print $2}')
    photo=$("$relight" eval data/room "$edit" data/room/photo.exr | awk '/^rel_rmse/ {print $2}')
    printf '%-24s %9s %9s\n' "$edit" "$ours" "$photo" >>out/room-scores.txt
done
echo "== relight render data/room --edit data/room/edits/back_off.json --debug-views out/room-debug-views"
"$relight" render data/room --edit data/room/edits/back_off.json -o out/room-back_off.png \
    --debug-views out/room-debug-views >/dev/null 2>&1
echo
echo "rel_rmse against data/room/truth (spec metric; noise floor of the data about 0.01):"
cat out/room-scores.txt
echo "main job done: out/room-<edit>.exr|png, out/room-<edit>.json, out/room-scores.txt,"
echo "  the pipeline's intermediate images for back_off in out/room-debug-views/ (index.json says what each shows)"
