#!/usr/bin/env bash
# Each bundled scene through a COLMAP model and back: its camera written by `relight export
# colmap`, then `relight import colmap` with its first photo, its mesh, its lights, objects,
# average reflectance and the first photo's lights_on; every edit relit from the scene and
# from the imported one (per-pixel display, default settings) and both scored against the
# scene's truth (`relight eval`). Prints rel_rmse / changed_rel_rmse side by side and
# whether the two relit images are the same pixel for pixel (oiiotool --diff, no
# difference allowed).
#   bash bench/colmap_same_scores.sh [SCENE_DIR ...]   (default: data/room data/cornell data/room-multi)
set -euo pipefail
cd "$(dirname "$0")/.."
relight=${RELIGHT:-./build/relight/relight}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(data/room data/cornell data/room-multi)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "command: bash bench/colmap_same_scores.sh ${*:-}"
printf '%-12s %-24s %17s %17s %s\n' scene edit "scene" "imported" "pixels"
score() {
    "$relight" eval "$1" "$2" "$3" |
        awk '/^rel_rmse/ {r = $2} /^changed_rel_rmse/ {c = $2} END {print r " / " c}'
}
for dir in "${scenes[@]}"; do
    name=$(basename "$dir")
    # What scene.json says beyond the camera, read with Python's json module.
    read -r mesh photo on reflectance < <(python3 -c '
import json, sys
s = json.load(open(sys.argv[1] + "/scene.json"))
p = s["photos"][0]
print(s["geometry"][0], p["file"], ",".join(p["lights_on"]), s.get("average_reflectance", 0.5))
' "$dir")
    mkdir -p "$work/$name/images"
    cp "$dir/$photo" "$work/$name/images/"
    "$relight" export colmap "$dir" -o "$work/$name/sparse" >/dev/null
    "$relight" import colmap "$work/$name/sparse" --image "$photo" --images "$work/$name/images" \
        --mesh "$dir/$mesh" --lights "$dir/scene.json" --objects "$dir/scene.json" \
        --lights-on "$on" --average-reflectance "$reflectance" -o "$work/$name/scene" >/dev/null
    for file in "$dir"/edits/*.json; do
        edit=$(basename "$file" .json)
        [ -f "$dir/truth/$edit.exr" ] || continue
        a="$work/$name-$edit.scene.exr"
        b="$work/$name-$edit.imported.exr"
        "$relight" render "$dir" --edit "$file" -o "$a" --cache "$work/$name.scene.bin" \
            >"$work/log" 2>&1
        "$relight" render "$work/$name/scene" --edit "$file" -o "$b" \
            --cache "$work/$name.imported.bin" >"$work/log" 2>&1
        same=different
        oiiotool --diff --fail 0 --failpercent 0 "$a" "$b" >/dev/null 2>&1 && same=same
        printf '%-12s %-24s %17s %17s %s\n' "$name" "$edit" "$(score "$dir" "$edit" "$a")" \
            "$(score "$dir" "$edit" "$b")" "$same"
    done
done
