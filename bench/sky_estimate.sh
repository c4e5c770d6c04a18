#!/usr/bin/env bash
# The courtyard with its sun's "irradiance" and its sky's "sh9" set to "estimate"
# (relight/pipeline/sky_estimate.h): the fitted values against scene.json's true ones, and
# every edit scored (`relight eval`, default per-pixel display) with the given lights and
# with the estimated ones. The estimate copy is made in a temporary folder (truth linked).
#   bash bench/sky_estimate.sh [SCENE_DIR]      (default: data/courtyard)
set -euo pipefail
cd "$(dirname "$0")/.."
relight=${RELIGHT:-./build/relight/relight}
src=${1:-data/courtyard}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "command: bash bench/sky_estimate.sh ${*:-}"
est="$work/estimate"
cp -r "$src" "$est"
python3 - "$est/scene.json" <<'PY'
import json, sys
p = sys.argv[1]
s = json.load(open(p))
for l in s["lights"]:
    if l["type"] == "sun": l["irradiance"] = "estimate"
    if l["type"] == "environment": l["sh9"] = "estimate"
json.dump(s, open(p, "w"), indent=1)
PY
"$relight" render "$est" -o "$work/identity.exr" --cache "$work/est.bin" \
    --report "$work/report.json" >"$work/log" 2>&1
python3 - "$src/scene.json" "$work/report.json" <<'PY'
import json, sys
truth = {l["name"]: l for l in json.load(open(sys.argv[1]))["lights"]}
est = json.load(open(sys.argv[2]))["estimated"]
fmt = lambda v: " ".join("%7.4f" % x for x in v)
for name, e in est.items():
    if "sh9" in e:
        print("sky %s: coefficient, fitted (r g b), true (r g b)" % name)
        for k, (f, t) in enumerate(zip(e["sh9"], truth[name]["sh9"])):
            print("  L%d  %s   %s" % (k, fmt(f), fmt(t)))
    if "irradiance" in e:
        print("sun %s irradiance: fitted %s, true %s" % (name, fmt(e["irradiance"]),
                                                      fmt(truth[name]["irradiance"])))
PY
grep -E "fits; rank" "$work/log" | sed 's/^ */fit: /'
grep -E "^time: prepare" "$work/log" | sed 's/^/estimate scene /'
score() {  # scene_dir edit cache
    local out="$work/$(basename "$1")-$2.exr"
    if "$relight" render "$1" --edit "$1/edits/$2.json" -o "$out" --cache "$3" >"$work/log" 2>&1; then
        "$relight" eval "$1" "$2" "$out" |
            awk '/^rel_rmse/ {r = $2} /^changed_rel_rmse/ {c = $2} END {print r " / " c}'
    else
        echo refused
    fi
}
printf '%-18s %20s %20s\n' edit "given lights" "estimated lights"
for file in "$src"/edits/*.json; do
    edit=$(basename "$file" .json)
    [ -f "$src/truth/$edit.exr" ] || continue
    printf '%-18s %20s %20s\n' "$edit" "$(score "$src" "$edit" "$work/given.bin")" \
        "$(score "$est" "$edit" "$work/est.bin")"
done
