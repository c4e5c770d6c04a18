#!/usr/bin/env bash
# Are two relight binaries' outputs the same, pixel for pixel? For changes meant to change
# no figure (a re-layout, a helper given one home): `relight solve` of the bundled scenes
# and `relight render` of edits that go through every path (light edits by superposition,
# virtual lights and objects through the solver), compared with oiiotool (no difference
# at all allowed). Prints one line per output and the command; exits 1 on any difference.
#   bash bench/same_outputs.sh OLD_RELIGHT NEW_RELIGHT [WORK_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1
new=$2
work=${3:-$(mktemp -d)}
mkdir -p "$work"
echo "command: bash bench/same_outputs.sh $*"
fail=0
compare() {  # name, then the relight arguments with OUT where the output goes
    local name=$1
    shift
    local a=() b=()
    for arg in "$@"; do
        a+=("${arg/OUT/$work/$name.old.exr}")
        b+=("${arg/OUT/$work/$name.new.exr}")
    done
    "$old" "${a[@]}" >"$work/$name.old.log" 2>&1
    "$new" "${b[@]}" >"$work/$name.new.log" 2>&1
    if oiiotool --diff --fail 0 --failpercent 0 "$work/$name.old.exr" "$work/$name.new.exr" \
        >"$work/$name.diff" 2>&1; then
        echo "SAME    $name"
    else
        echo "DIFFER  $name ($(grep -m1 -i 'Max error' "$work/$name.diff" | xargs))"
        fail=1
    fi
}
compare solve_room solve data/room -o OUT
compare solve_cornell solve data/cornell -o OUT
for e in back_off virtual_light_and_box virtual_box_moved; do
    compare "render_room_$e" render data/room --edit "data/room/edits/$e.json" --no-cache -o OUT
done
for e in light_colour virtual_box; do
    compare "render_cornell_$e" render data/cornell --edit "data/cornell/edits/$e.json" \
        --no-cache -o OUT
done
exit $fail
