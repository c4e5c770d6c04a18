#!/usr/bin/env bash
# Time per removal at 320x240 and 1280x960 (issue 34's figures): every removal edit of
# data/room and data/furnished rendered by `relight render` (default per-pixel display, no
# cache: a user's first render), at the photo's size and with the photo upscaled 4 times
# (../shared/tools/tessellate.py N=1 --upscale 4: the same model, the camera scaled).
# Prints the removal's time as render reports it (the solver's update, the region's
# relighting and the fill), the fill's share, the whole edit and the process's peak memory.
#   bash bench/removal_times.sh [RELIGHT] [WORK_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
relight=${1:-./build/relight/relight}
work=${2:-$(mktemp -d)}
mkdir -p "$work"
echo "command: bash bench/removal_times.sh $*"
printf '%-10s %-18s %-9s %10s %8s %8s %8s\n' scene edit size removal_s fill_s edit_s peak_MB
for scene in room furnished; do
    python3 ../shared/tools/tessellate.py "data/$scene" "$work/$scene-x4" 1 --upscale 4 >/dev/null
    for edit in $(ls "data/$scene/edits" | grep '^remove_' | sed 's/\.json$//'); do
        for size in 320x240 1280x960; do
            dir=data/$scene
            [ "$size" = 1280x960 ] && dir=$work/$scene-x4
            log=$work/$scene-$edit-$size.log
            /usr/bin/time -f "peak %M" "$relight" render "$dir" --edit "$dir/edits/$edit.json" \
                -o "$work/$scene-$edit-$size.exr" --no-cache >"$log" 2>&1
            line=$(grep -E "^removed object" "$log" | head -1)
            removal=$(echo "$line" | grep -oE "[0-9.]+ s \(" | tr -dc '0-9.')
            fill=$(echo "$line" | grep -oE "[0-9.]+ s of it the fill" | grep -oE "^[0-9.]+")
            whole=$(grep -oE "edit [0-9.]+ s" "$log" | tr -dc '0-9.')
            peak=$(awk '/^peak /{printf "%.0f", $2 / 1024}' "$log")
            printf '%-10s %-18s %-9s %10s %8s %8s %8s\n' "$scene" "$edit" "$size" "$removal" \
                "$fill" "$whole" "$peak"
        done
    done
done
