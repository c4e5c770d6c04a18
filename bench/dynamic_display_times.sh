#!/usr/bin/env bash
# The ratio map's (000 Eq. 3, `--display ratio-map`) edit time and image on the courtyard's
# edits that go through DynamicRelighting (a light moved or added, an object added), this
# build's relight against another build's (BASE, e.g. main's), alternating, 3 runs each; the
# images compared bit for bit (idiff -fail 0).
#   BASE=/path/to/main/build/relight/relight bash bench/dynamic_display_times.sh [DISPLAY]
set -euo pipefail
cd "$(dirname "$0")/.."
base=${BASE:?set BASE to the relight binary to compare with}
new=${RELIGHT:-./build/relight/relight}
display=${1:-ratio-map}
w=$(mktemp -d)
trap 'rm -rf "$w"' EXIT
echo "command: BASE=$base bash bench/dynamic_display_times.sh $display"
printf '%-16s %-5s %s\n' edit build "edit_s (3 runs)"
for e in sun_moved evening night_lamp virtual_box; do
    for b in base new; do
        bin=$base
        [ $b = new ] && bin=$new
        ts=()
        for i in 1 2 3; do
            "$bin" render data/courtyard --edit "data/courtyard/edits/$e.json" --display "$display" \
                -o "$w/$b-$e.exr" --cache "$w/$b.bin" --report "$w/r.json" >/dev/null 2>&1
            ts+=("$(python3 -c "import json; print('%.3f' % json.load(open('$w/r.json'))['time_s']['edit'])")")
        done
        printf '%-16s %-5s %s\n' "$e" "$b" "${ts[*]}"
    done
    if idiff -fail 0 -failpercent 0 "$w/base-$e.exr" "$w/new-$e.exr" >/dev/null; then
        echo "  $e: the same image bit for bit"
    else
        echo "  $e: the images differ"
    fi
done
