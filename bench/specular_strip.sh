#!/bin/bash
# The README picture of the specular pass (docs/specular-box.png): data/room's
# edits/virtual_box_specular.json rendered with and without the box's "specular" term
# (per-pixel display), cropped around the box, 4x, side by side (left: without), sRGB 8-bit.
#   bash bench/specular_strip.sh [OUT.png]   (from the repository root, after a build)
set -euo pipefail
out=${1:-docs/specular-box.png}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
relight=build/relight/relight
edit=data/room/edits/virtual_box_specular.json
echo "command: bash bench/specular_strip.sh $out"
# The same edit without its term: the box file made absolute, the "specular" entry dropped.
sed -e "s#\.\./objects/box\.obj#$PWD/data/room/objects/box.obj#" "$edit" |
    tr '\n' '\r' | sed -e 's/,\r *"specular": {[^}]*}//' | tr '\r' '\n' >"$work/matte.json"
"$relight" render data/room --edit "$edit" -o "$work/specular.exr" --cache "$work/room.bin" >/dev/null
"$relight" render data/room --edit "$work/matte.json" -o "$work/matte.exr" \
    --cache "$work/room.bin" >/dev/null
idiff -fail 0 "$work/matte.exr" "$work/specular.exr" | grep -E "Max error|over 0" || true
crop="--cut 56x48+94+146 --resample 224x192"
oiiotool "$work/matte.exr" $crop "$work/specular.exr" $crop --mosaic:pad=4 2x1 \
    --colorconvert linear sRGB -d uint8 -o "$out"
echo "wrote $out"
